#include "measurement/shader_probe.hpp"
#include "render/renderer.hpp"

#include "core/install_paths.hpp"
#include "hilite/core/error.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "hilite/scene/resolve.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <thread>
#include <vector>

#ifndef HILITE_INSTALL_LIBEXEC_DIR
#define HILITE_INSTALL_LIBEXEC_DIR "/usr/local/libexec"
#endif

namespace hilite::measurement {

namespace {

constexpr int kProbeSize = 8;

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

/// The helper that runs the probe (hilite-probe), when set by setProbeExecutable.
std::string& probeOverride() {
    static std::string path;
    return path;
}

/// hilite-probe, found relative to the code that runs (core/install_paths.hpp): beside it (<build>/bin), in
/// <prefix>/libexec (beside <prefix>/lib or <prefix>/bin) or in the Python package's libexec/, else in the
/// install prefix compiled in. SystemError naming every place tried if none holds it.
std::string probeExecutable() {
    if (!probeOverride().empty()) return probeOverride();
    std::vector<std::string> tried;
    for (const std::string& dir : {objectDirectory(), executableDirectory()}) {
        if (dir.empty()) continue;
        for (const std::string& candidate :
             {dir + "/hilite-probe", dir + "/../libexec/hilite-probe", dir + "/libexec/hilite-probe"}) {
            if (access(candidate.c_str(), X_OK) == 0) return candidate;
            if (std::find(tried.begin(), tried.end(), candidate) == tried.end()) tried.push_back(candidate);
        }
    }
    const std::string installed = std::string(HILITE_INSTALL_LIBEXEC_DIR) + "/hilite-probe";
    if (access(installed.c_str(), X_OK) == 0) return installed;
    tried.push_back(installed + " (the install prefix compiled in)");
    std::string list;
    for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t;
    throw SystemError("shader probe: the helper hilite-probe not found (looked in " + list + ")");
}

/// The child's command line: the scene's .brdf, its values and light, nothing else.
std::vector<std::string> probeArgs(const std::string& exe, const render::Scene& s, const std::string& backend,
                                   int gpu) {
    std::vector<std::string> a = {exe, "--brdf", s.brdfFile->path};
    for (const std::string& v : brdf_file::valueAssignments(*s.brdfFile)) a.insert(a.end(), {"--param", v});
    a.insert(a.end(), {"--incidence", number(s.light.incidenceDeg), "--azimuth", number(s.light.azimuthDeg),
                       "--tangent-angle", number(s.brdf.tangentAngleDeg), "--light", render::toString(s.light.type),
                       "--light-distance", number(s.light.distance), "--distance", number(s.eyeDistance)});
    if (!backend.empty()) a.insert(a.end(), {"--gl-backend", backend});
    if (gpu >= 0) a.insert(a.end(), {"--gpu", std::to_string(gpu)});
    return a;
}

/// Reads the child's stderr until it closes or the deadline passes; false at the deadline.
bool readUntil(int fd, std::chrono::steady_clock::time_point deadline, std::string& out) {
    char buf[4096];
    for (;;) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) return false;
        pollfd p{fd, POLLIN, 0};
        const int r = poll(&p, 1, int(std::min<long long>(left.count(), 1000)));
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) return true;
        if (r == 0) continue;
        const ssize_t n = read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return true;  // closed: the child is ending
        if (out.size() < 65536) out.append(buf, size_t(n));
    }
}

/// Waits for the child until the deadline; false (child still running) at the deadline.
bool waitUntil(pid_t pid, std::chrono::steady_clock::time_point deadline, int& status) {
    for (;;) {
        const pid_t r = waitpid(pid, &status, WNOHANG);
        if (r == pid) return true;
        if (r < 0 && errno != EINTR) return true;
        if (std::chrono::steady_clock::now() >= deadline) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
}

/// The child's own one-line error: its last "hilite: " line (the GL driver may print warnings first), or "".
std::string childError(const std::string& err) {
    std::string found;
    size_t start = 0;
    while (start < err.size()) {
        const size_t end = std::min(err.find('\n', start), err.size());
        if (err.compare(start, 8, "hilite: ") == 0) found = err.substr(start + 8, end - start - 8);
        start = end + 1;
    }
    return found;
}

/// The last non-blank line of the child's stderr, control characters shown as '?', at most 200 characters.
std::string lastLine(const std::string& err) {
    size_t end = err.size();
    while (end > 0 && std::isspace(static_cast<unsigned char>(err[end - 1]))) --end;
    if (end == 0) return "";
    const size_t begin = err.rfind('\n', end - 1);
    std::string line =
        err.substr(begin == std::string::npos ? 0 : begin + 1, end - (begin == std::string::npos ? 0 : begin + 1));
    for (char& c : line)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return line.size() > 200 ? line.substr(0, 200) + "..." : line;
}

}  // namespace

void setProbeExecutable(const std::string& path) { probeOverride() = path; }

std::string probeFailure(const std::string& path, int status, const std::string& err) {
    const std::string tail = lastLine(err);
    const std::string said = tail.empty() ? "it printed nothing" : "its last output: '" + tail + "'";
    if (WIFSIGNALED(status)) {
        const int sig = WTERMSIG(status);
        const char* abbrev = sigabbrev_np(sig);
        const char* text = strsignal(sig);
        return path + ": the shader probe (a child process compiling and drawing the shader) was killed by signal " +
               std::to_string(sig) + " (" + (abbrev ? "SIG" + std::string(abbrev) : "unknown") +
               (text ? ", " + std::string(text) : "") + "): the GL driver crashed on this shader; " + said;
    }
    if (WIFEXITED(status))
        return path + ": the shader probe (a child process compiling and drawing the shader) ended with exit status " +
               std::to_string(WEXITSTATUS(status)) + (WEXITSTATUS(status) == 127 ? " (hilite could not be run)" : "") +
               "; " + said;
    return path + ": the shader probe ended abnormally (wait status " + std::to_string(status) + "); " + said;
}

void probeShader(const render::Scene& scene, const std::string& backend, double timeoutSeconds, int gpu) {
    if (!scene.brdfFile) return;
    const std::vector<std::string> args = probeArgs(probeExecutable(), scene, backend, gpu);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) throw SystemError("shader probe: pipe failed");
    const auto start = std::chrono::steady_clock::now();
    const auto deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(timeoutSeconds));
    const pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]), close(fds[1]);
        throw SystemError("shader probe: fork failed");
    }
    if (pid == 0) {  // the child: only async-signal-safe calls until exec
        dup2(fds[1], STDERR_FILENO);
        const int null = open("/dev/null", O_WRONLY);
        if (null >= 0) dup2(null, STDOUT_FILENO);
        execv(argv[0], argv.data());
        _exit(127);
    }
    close(fds[1]);
    std::string err;
    int status = 0;
    const bool finished = readUntil(fds[0], deadline, err) && waitUntil(pid, deadline, status);
    close(fds[0]);
    if (!finished) {
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        char limit[32];
        std::snprintf(limit, sizeof limit, "%g", timeoutSeconds);
        throw InputError(scene.brdfFile->path + ": shader took longer than " + limit + " s on a probe render (" +
                         std::to_string(kProbeSize) + "x" + std::to_string(kProbeSize) +
                         " pixels, in a child process); stopped (raise --shader-timeout if it is only slow)");
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
    const std::string own = childError(err);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 2 && !own.empty()) throw InputError(own);
    // A crash (a Mesa compiler abort printed no "hilite:" line and left the reason empty) is the shader's:
    // exit 2 naming the file. A child that could not start or found no GL is the system's: exit 3.
    const bool system = WIFEXITED(status) && (WEXITSTATUS(status) == 3 || WEXITSTATUS(status) == 127);
    const std::string why = own.empty() || !WIFEXITED(status) ? probeFailure(scene.brdfFile->path, status, err)
                                                              : scene.brdfFile->path + ": shader probe: " + own;
    if (system) throw SystemError(why);
    throw InputError(why);
}

/// The child: compile both outputs and render the probe views; any failure is the usual one-line error.
void runShaderProbe(render::Scene scene, gl::Backend backend, int gpu) {
    const double incidence = scene.light.incidenceDeg;
    gl::Context context(backend, gpu);
    render::Renderer renderer(context);
    ImageF img;
    for (double inc : {incidence, 0.0, 45.0, 80.0}) {
        scene.light.incidenceDeg = inc;
        const dvec3 wr = scene.light.chart().wr();
        for (double fov : {160.0, 2.0})
            for (auto out : {render::Output::Measure, render::Output::Color})
                renderer.render(scene, measurementCamera(scene, wr, fov, kProbeSize, kProbeSize), out, img);
    }
}

/// hilite-probe's main: `--name value` pairs (the registry's names, '-' for '_', as probeArgs writes them),
/// resolved as a render; exit 0, or the one-line error as "hilite: ..." with exit 2 (input) or 3 (system).
int probeMain(int argc, char** argv) {
    try {
        scene::Values values;
        for (int i = 1; i < argc; i += 2) {
            std::string flag = argv[i];
            if (flag.rfind("--", 0) != 0 || i + 1 >= argc)
                throw InputError("hilite-probe: expected --name value pairs, got '" + flag + "'");
            flag = flag.substr(2);
            std::replace(flag.begin(), flag.end(), '-', '_');
            values.set(flag, argv[i + 1]);
        }
        const scene::Resolved r = scene::resolve(values, scene::Purpose::Render);
        // Test hook: a GL driver crash cannot be provoked on purpose, so tests/cli/test_hostile.cpp makes
        // this child die of the named signal after a line on stderr, as a Mesa compiler abort does.
        if (const char* sig = std::getenv("HILITE_TEST_PROBE_SIGNAL"); sig && std::atoi(sig) > 0) {
            std::fprintf(stderr, "test: simulated shader compiler crash\n");
            std::signal(std::atoi(sig), SIG_DFL);
            std::raise(std::atoi(sig));
        }
        runShaderProbe(r.scene, scene::backendOf(r), r.gpu);
        return 0;
    } catch (const InputError& e) {
        std::cerr << "hilite: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "hilite: " << e.what() << "\n";
        return 3;
    }
}

}  // namespace hilite::measurement
