#include "hilite/experiments/cluster.hpp"

#include "core/text.hpp"
#include "experiments/experiment.hpp"
#include "hilite/core/error.hpp"
#include "io/image_io.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace hilite::experiments {

namespace fs = std::filesystem;

namespace {

/// `s` as one shell word: single-quoted, a quote inside written '\'' (a file's name is data, never shell code).
std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

/// The program `name` on $PATH ("" when absent).
std::string findOnPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    for (const std::string& d : split(path ? path : "", ':')) {
        const std::string p = (d.empty() ? std::string(".") : d) + "/" + name;
        if (::access(p.c_str(), X_OK) == 0 && fs::is_regular_file(p)) return p;
    }
    return "";
}

struct Ran {
    int status = -1;  ///< the exit status; -1: did not exit normally
    std::string out, err;
};

/// Runs argv (no shell) and collects its output.
Ran runProgram(const std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    int out[2], err[2];
    if (pipe2(out, O_CLOEXEC) != 0) throw SystemError(args[0] + ": pipe failed");
    if (pipe2(err, O_CLOEXEC) != 0) {
        close(out[0]), close(out[1]);
        throw SystemError(args[0] + ": pipe failed");
    }
    const pid_t pid = fork();
    if (pid < 0) {
        close(out[0]), close(out[1]), close(err[0]), close(err[1]);
        throw SystemError(args[0] + ": fork failed");
    }
    if (pid == 0) {  // the child: only async-signal-safe calls until exec
        dup2(out[1], STDOUT_FILENO);
        dup2(err[1], STDERR_FILENO);
        execv(argv[0], argv.data());
        _exit(127);
    }
    close(out[1]), close(err[1]);
    Ran r;
    pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
    for (int open = 2; open > 0;) {
        if (::poll(fds, 2, -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            char buf[4096];
            const ssize_t n = ::read(fds[i].fd, buf, sizeof buf);
            if (n > 0) (i == 0 ? r.out : r.err).append(buf, size_t(n));
            else close(fds[i].fd), fds[i].fd = -1, --open;
        }
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

/// Rows (complete lines) in a results.jsonl; 0 when absent. Counted, not parsed: status reads many shards.
size_t countRows(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    size_t n = 0;
    char buf[65536];
    while (in.read(buf, sizeof buf) || in.gcount() > 0) n += size_t(std::count(buf, buf + in.gcount(), '\n'));
    return n;
}

/// The last non-empty line of a (log) file, from its last 64 KiB; "" when none.
std::string lastLine(const std::string& file) {
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    if (!in) return "";
    const std::streamoff size = in.tellg();
    const std::streamoff from = std::max<std::streamoff>(0, size - 65536);
    in.seekg(from);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string last;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    return last;
}

/// Configurations i with i mod n == k - 1 among `c`.
size_t shardSize(size_t c, int k, int n) { return size_t(k) > c ? 0 : (c - size_t(k)) / size_t(n) + 1; }

/// "1-4", "2,5-7": Slurm's --array list of the given (sorted) shards.
std::string arrayList(const std::vector<int>& ks) {
    std::string s;
    for (size_t i = 0; i < ks.size();) {
        size_t j = i;
        while (j + 1 < ks.size() && ks[j + 1] == ks[j] + 1) ++j;
        s += (s.empty() ? "" : ",") + std::to_string(ks[i]) + (j > i ? "-" + std::to_string(ks[j]) : "");
        i = j + 1;
    }
    return s;
}

/// The job id of `sbatch --parsable`'s output ("123" or "123;cluster").
std::string jobId(const std::string& out) {
    std::string id = out.substr(0, out.find_first_of(";\n"));
    id.erase(std::remove_if(id.begin(), id.end(), [](char c) { return c == ' ' || c == '\r'; }), id.end());
    return id;
}

/// Whether job `id` is still in the queue (pending or running): squeue lists it.
bool inQueue(const std::string& squeue, const std::string& id) {
    if (id.empty()) return false;
    const Ran r = runProgram({squeue, "-h", "-j", id, "-o", "%i"});
    return r.status == 0 && r.out.find_first_not_of(" \n") != std::string::npos;
}

/// Whether merge job `merge`, behind array job `array` of `tasks` tasks now out of the queue, waits on a dependency
/// that can no longer be met: a task failed or was cancelled (even after its shard's last row). Slurm keeps such a
/// job pending for ever, reason DependencyNeverSatisfied, but names that reason only at its next scheduling pass:
/// until then the array's ended tasks say it (squeue keeps them for MinJobAge, 300 s by default; a task cancelled
/// while pending leaves no record, so fewer COMPLETED than submitted says it too).
bool neverRuns(const std::string& squeue, const std::string& merge, const std::string& array, size_t tasks) {
    if (merge.empty()) return false;
    const Ran r = runProgram({squeue, "-h", "-j", merge, "-o", "%r"});
    if (r.status != 0) return false;
    if (r.out.find("DependencyNeverSatisfied") != std::string::npos) return true;
    if (array.empty() || r.out.find("Dependency") == std::string::npos) return false;
    const Ran ended = runProgram({squeue, "-h", "-t", "all", "-j", array, "-o", "%T"});
    if (ended.status != 0) return false;
    size_t completed = 0;
    std::istringstream states(ended.out);
    for (std::string state; states >> state;) {
        if (state == "COMPLETED") ++completed;
        else if (state != "COMPLETING") return true;  // CANCELLED, FAILED, TIMEOUT, NODE_FAIL, OUT_OF_MEMORY, ...
    }
    return completed < tasks;
}

nlohmann::json readSubmitted(const std::string& dir) {
    const std::string file = dir + "/slurm/submit.json";
    std::ifstream in(file);
    if (!in) throw InputError(dir + ": no submitted run here (" + file + " is missing): hilite submit writes it");
    try {
        nlohmann::json j = nlohmann::json::parse(in);
        for (const char* key : {"experiment", "name", "shards", "configurations"})
            if (!j.contains(key)) throw InputError(file + ": no \"" + key + "\"");
        return j;
    } catch (const nlohmann::json::exception& e) {
        throw InputError(file + ": not a submitted run's record (" + e.what() + ")");
    }
}

}  // namespace

const std::vector<std::string>& submitEngines() {
    static const std::vector<std::string> engines{"slurm"};
    return engines;
}

SubmitResult submitExperiment(const SubmitOptions& o) {
    // Everything checked before anything is written or submitted.
    if (std::find(submitEngines().begin(), submitEngines().end(), o.engine) == submitEngines().end())
        throw InputError("--engine: unknown '" + o.engine + "' (allowed: slurm)");
    if (o.out.empty()) throw InputError(o.outName + ": submit needs an output folder");
    if (o.out.find('%') != std::string::npos)
        throw InputError(o.outName + ": '" + o.out + "' holds '%', which Slurm reads as a file-name pattern");
    const std::string dir = fs::absolute(o.out).lexically_normal().string();
    nlohmann::json before;
    if (o.resume) before = readSubmitted(dir);
    else if (fs::exists(dir + "/slurm/submit.json"))
        throw InputError(o.outName + ": " + o.out +
                         " already holds a submitted run (slurm/submit.json): follow it with hilite status " + o.out +
                         ", or resubmit its missing shards with --resume");
    const std::string given =
        o.experiment.empty() && o.resume ? before["experiment"].get<std::string>() : findExperiment(o.experiment);
    const std::string experimentPath = fs::absolute(given).lexically_normal().string();
    if (o.resume && experimentPath != before["experiment"].get<std::string>())
        throw InputError("--resume: " + o.out + " was submitted for " + before["experiment"].get<std::string>() +
                         ", not " + experimentPath);
    const Experiment exp = loadExperiment(experimentPath);
    const auto configs = exp.configurations();  // validates every configuration
    const int shards = o.resume && o.shards == 0 ? before["shards"].get<int>() : o.shards;
    if (o.resume && shards != before["shards"].get<int>())
        throw InputError("--shards: " + o.out + " was submitted in " + before["shards"].dump() + " shards, not " +
                         std::to_string(shards));
    if (shards < 1 || size_t(shards) > configs.size())
        throw InputError("--shards: expected 1 to " + std::to_string(configs.size()) +
                         " (the experiment's configurations), got " + std::to_string(shards));
    if (o.hilite.empty() || ::access(o.hilite.c_str(), X_OK) != 0)
        throw InputError("submit: the hilite program '" + o.hilite + "' is not executable");
    io::checkOutputDir(dir, o.outName);
    io::checkUnlocked(dir, o.outName);
    const std::string sbatch = findOnPath("sbatch");
    if (!o.dryRun && sbatch.empty())
        throw InputError(
            "submit: sbatch (Slurm's client) is not on PATH: install Slurm's client (Debian: slurm-client) "
            "or write the scripts only with --dry-run");
    // The earlier submission's jobs: its array still queued or running would write the same shards (refused); its
    // merge pending behind a failed array can never run (Slurm keeps it for ever): cancelled, a new one follows.
    std::string staleMerge;
    if (o.resume && !o.dryRun) {
        const std::string squeue = findOnPath("squeue");
        const std::string array = before.value("array_job", std::string()), merge = before.value("merge_job", "");
        if (!squeue.empty() && inQueue(squeue, array))
            throw InputError("--resume: array job " + array + " of " + o.out +
                             " is still queued or running: wait for it, or scancel it first");
        if (!squeue.empty() && inQueue(squeue, merge)) {
            size_t rows = 0;
            for (int k = 1; k <= before["shards"].get<int>(); ++k)
                rows += countRows(dir + "/shards/" + std::to_string(k) + "/results.jsonl");
            if (rows >= before["configurations"].get<size_t>() &&
                !neverRuns(squeue, merge, array, before.value("submitted", nlohmann::json::array()).size()))
                throw InputError("--resume: merge job " + merge + " of " + o.out +
                                 " is queued or running and every shard is complete: wait for it");
            staleMerge = merge;
        }
    }

    SubmitResult r;
    r.dir = dir, r.name = exp.name, r.configurations = configs.size(), r.shards = shards;
    for (int k = 1; k <= shards; ++k)
        if (!o.resume ||
            countRows(dir + "/shards/" + std::to_string(k) + "/results.jsonl") < shardSize(configs.size(), k, shards))
            r.submitted.push_back(k);

    if (!staleMerge.empty()) {
        const std::string scancel = findOnPath("scancel");
        if (!scancel.empty()) runProgram({scancel, staleMerge});
    }
    io::makeOutputDir(dir, o.outName);
    fs::create_directories(dir + "/slurm/logs");
    fs::create_directories(dir + "/shards");
    const std::string slurm = dir + "/slurm";
    const std::string backend = o.backend.empty() ? "" : " --gl-backend " + shellQuote(o.backend);
    std::ostringstream array, merge;
    array << "#!/bin/bash\n"
          << "# hilite submit: one array task per shard of " << exp.name << " (" << configs.size()
          << " configurations in " << shards << " shards); task K writes shards/K, resuming what it has.\n"
          << "set -eu\n"
          << "k=${SLURM_ARRAY_TASK_ID:?run it as an array task (sbatch --array), or set SLURM_ARRAY_TASK_ID}\n"
          << "exec " << shellQuote(o.hilite) << " run " << shellQuote(experimentPath) << " -o "
          << shellQuote(dir + "/shards/") << "\"$k\" --shard \"$k/" << shards << "\" --resume" << backend << "\n";
    merge << "#!/bin/bash\n"
          << "# hilite submit: the shards of " << exp.name << " merged into the folder, as a single run writes it;\n"
          << "# its exit status goes to slurm/merge.rc (hilite submit --wait and hilite status read it).\n"
          << "set -u\n"
          << shellQuote(o.hilite) << " merge";
    for (int k = 1; k <= shards; ++k) merge << " " << shellQuote(dir + "/shards/" + std::to_string(k));
    merge << " -o " << shellQuote(dir) << backend << "\n"
          << "rc=$?\n"
          << "echo \"$rc\" > " << shellQuote(slurm + "/merge.rc") << "\n"
          << "exit \"$rc\"\n";
    io::writeFileAtomic(slurm + "/array.sbatch", array.str());
    io::writeFileAtomic(slurm + "/merge.sbatch", merge.str());
    ::chmod((slurm + "/array.sbatch").c_str(), 0755);
    ::chmod((slurm + "/merge.sbatch").c_str(), 0755);
    std::remove((slurm + "/merge.rc").c_str());  // a resubmitted merge's status is its own

    const std::string program = sbatch.empty() ? "sbatch" : sbatch;
    std::vector<std::string> arrayCmd;
    if (!r.submitted.empty()) {
        arrayCmd = {program,
                    "--parsable",
                    "--job-name=hilite-" + exp.name,
                    "--array=" + arrayList(r.submitted),
                    "--output=" + slurm + "/logs/shard-%a.out",
                    "--error=" + slurm + "/logs/shard-%a.err"};
        arrayCmd.insert(arrayCmd.end(), o.sbatchArgs.begin(), o.sbatchArgs.end());
        arrayCmd.push_back(slurm + "/array.sbatch");
    }
    auto mergeCmd = [&](const std::string& after) {
        std::vector<std::string> c{program, "--parsable", "--job-name=hilite-" + exp.name + "-merge"};
        if (!after.empty()) c.push_back("--dependency=afterok:" + after);
        c.insert(c.end(), {"--output=" + slurm + "/logs/merge.out", "--error=" + slurm + "/logs/merge.err"});
        c.insert(c.end(), o.sbatchArgs.begin(), o.sbatchArgs.end());
        c.push_back(slurm + "/merge.sbatch");
        return c;
    };
    auto submit = [&](const std::vector<std::string>& cmd) {
        const Ran ran = runProgram(cmd);
        const std::string id = jobId(ran.out);
        if (ran.status != 0 || id.empty() || id.find_first_not_of("0123456789_") != std::string::npos) {
            const std::string said = ran.err.empty() ? ran.out : ran.err;
            throw SystemError("submit: sbatch failed (exit " + std::to_string(ran.status) +
                              "): " + said.substr(0, said.find_last_not_of('\n') + 1));
        }
        return id;
    };
    nlohmann::json record = {{"engine", o.engine},      {"experiment", experimentPath},     {"name", exp.name},
                             {"shards", shards},        {"configurations", configs.size()}, {"hilite", o.hilite},
                             {"submitted", r.submitted}};
    if (o.dryRun) {
        if (!arrayCmd.empty()) r.commands.push_back(arrayCmd);
        r.commands.push_back(mergeCmd(arrayCmd.empty() ? "" : "ARRAY_JOB_ID"));
    } else {
        if (!arrayCmd.empty()) {
            r.commands.push_back(arrayCmd);
            r.arrayJob = submit(arrayCmd);
        }
        r.commands.push_back(mergeCmd(r.arrayJob));
        r.mergeJob = submit(r.commands.back());
        record["array_job"] = r.arrayJob;
        record["merge_job"] = r.mergeJob;
    }
    record["commands"] = r.commands;
    io::writeFileAtomic(slurm + "/submit.json", record.dump(2) + "\n");
    return r;
}

ClusterStatus clusterStatus(const std::string& dirIn) {
    const std::string dir = fs::absolute(dirIn).lexically_normal().string();
    const nlohmann::json j = readSubmitted(dir);
    ClusterStatus s;
    s.dir = dir, s.name = j["name"].get<std::string>();
    s.configurations = j["configurations"].get<size_t>(), s.shards = j["shards"].get<int>();
    s.arrayJob = j.value("array_job", std::string()), s.mergeJob = j.value("merge_job", std::string());
    for (int k = 1; k <= s.shards; ++k) {
        ShardStatus sh;
        sh.shard = k;
        sh.expected = shardSize(s.configurations, k, s.shards);
        sh.rows = std::min(sh.expected, countRows(dir + "/shards/" + std::to_string(k) + "/results.jsonl"));
        if (sh.rows < sh.expected) sh.lastError = lastLine(dir + "/slurm/logs/shard-" + std::to_string(k) + ".err");
        s.rows += sh.rows;
        s.shard.push_back(sh);
    }
    std::ifstream rc(dir + "/slurm/merge.rc");
    if (rc >> s.mergeStatus) s.merged = true;
    s.mergedRows = countRows(dir + "/results.jsonl");
    return s;
}

ClusterStatus waitForCluster(const std::string& dir, double pollSeconds,
                             const std::function<void(const ClusterStatus&)>& progress) {
    const std::string squeue = findOnPath("squeue");
    if (squeue.empty()) throw InputError("--wait: squeue (Slurm's client) is not on PATH");
    for (bool last = false;;) {
        ClusterStatus s = clusterStatus(dir);
        if (progress) progress(s);
        if (s.merged || last) return s;
        if (!inQueue(squeue, s.arrayJob)) {
            const bool complete = s.rows == s.configurations;
            if (!complete) {  // a task failed or was cancelled: afterok can never be met
                const std::string scancel = findOnPath("scancel");
                if (!scancel.empty() && inQueue(squeue, s.mergeJob)) runProgram({scancel, s.mergeJob});
                return s;
            }
            last = !inQueue(squeue, s.mergeJob);  // gone without merge.rc: look once more, then report
        }
        std::this_thread::sleep_for(std::chrono::duration<double>(pollSeconds));
    }
}

}  // namespace hilite::experiments
