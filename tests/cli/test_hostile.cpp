// A hostile user's corpus, table-driven: bad flags, scene files, .brdf files, NDF tables, input and output
// paths and result folders. Each case asserts the exit code, a one-line message naming the flag or
// file:line(:key), and that every file in the scratch folder is left exactly as it was (nothing written,
// nothing replaced, nothing removed). Then the fault tests: a full disk mid-run, two concurrent runs into
// one folder, --resume after an edit, merge of shards of different experiments, damaged rows.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace hilite_test;

namespace {

struct Case {
    std::string args;      ///< hilite's arguments; {d} stands for the scratch folder
    int code;              ///< the exit code expected
    std::string needle;    ///< what the one-line message must contain ({d} replaced too)
    std::string env = "";  ///< NAME=VALUE set for this case only ("": none)
};

std::string subst(std::string s, const std::string& dir) {
    for (size_t i; (i = s.find("{d}")) != std::string::npos;) s.replace(i, 3, dir);
    return s;
}

/// Every entry below `root` (not following symlinks): its type and, for regular files, its bytes.
std::map<std::string, std::string> snapshot(const fs::path& root) {
    std::map<std::string, std::string> out;
    for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
        const auto st = it->symlink_status();
        std::string v = std::to_string(int(st.type())) + ":";
        if (st.type() == fs::file_type::regular) {
            std::ifstream in(it->path(), std::ios::binary);
            v += std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        } else if (st.type() == fs::file_type::symlink) {
            v += fs::read_symlink(it->path()).string();
        }
        out[it->path().string()] = v;
    }
    return out;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

const char* kBrdf = R"(analytic
::begin parameters
float alpha 0.0001 10 0.1
::end parameters
::begin shader
vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y ) { return vec3(alpha); }
::end shader
)";

const char* kSmall = R"([experiment]
name = "tiny"
[scene.camera]
size = "64"
[[sweep]]
key = "light.incidence"
values = [0, 30, 60]
)";

/// The scratch folder: a scene, a .brdf, an NDF table, an experiment, an existing output, a finished run,
/// a folder, a FIFO, a symlink and a regular file where folders are expected. Cases must leave it as it is.
struct Scratch : TempDir {
    Scratch() : TempDir("hilite-hostile") {
        write("ok.toml", "[material]\nmodel = \"ggx\"\nroughness = 0.2\n");
        write("ok.brdf", kBrdf);
        write("ok.csv", "theta_h_deg, D\n0, 10\n10, 5\n20, 1\n40, 0\n");
        write("tiny.toml", kSmall);
        write("brdfexp.toml",
              "[scene.material]\nbrdf = \"ok.brdf\"\n[[sweep]]\nkey = \"light.incidence\"\nvalues = [0, 30]\n");
        write("fov0.toml", std::string(kSmall) + "[[sweep]]\nkey = \"camera.fov\"\nvalues = [\"auto\", 0]\n");
        write("fovword.toml", std::string(kSmall) + "[[sweep]]\nkey = \"camera.fov\"\nvalues = [\"automatic\"]\n");
        write("elevword.toml", std::string(kSmall) + "[[sweep]]\nkey = \"camera.elevation\"\nrange = [-10, 10, 10]\n");
        write("existing.png", "not really a png, but it must survive");
        write("file.txt", "a regular file");
        fs::create_directories(path / "dir");
        mkfifo((*this / "fifo").c_str(), 0644);
        fs::create_symlink(*this / "existing.png", path / "link.png");
        fs::create_symlink("/dev/null", path / "devlink");
        fs::create_directories(path / "runlink");
        fs::create_symlink(*this / "file.txt", path / "runlink" / "results.jsonl");
    }
};

std::vector<Case> flagCases() {
    std::vector<Case> cases;
    const std::string measure = "measure --size 32 ";
    // Every numeric flag: not a number, empty, out of range, non-finite.
    const std::vector<std::pair<std::string, std::vector<std::string>>> numbers = {
        {"--roughness", {"-1", "nan", "inf", "''", "abc", "1e400", "0x10", "1,2"}},
        {"--exponent", {"-5", "nan", "''", "1e999"}},
        {"--incidence",
         {"91", "-1", "nan", "''", "0:90:inf", "0:90:0", "90:0:5", "1,,2", "0:90", "0:90:5:1", "0:1e9:1e-9"}},
        {"--azimuth", {"nan", "inf", "''", "x"}},
        {"--size", {"0", "-5", "16385", "1.5", "10x", "x10", "''", "1e9"}},
        {"--bump-seed", {"9007199254740993", "-1", "1.5", "''", "1e300"}},
        {"--fov", {"180", "-1", "nan", "''", "0", "-0", "automatic", "Auto", "auto,30"}},  // 0 once meant automatic
        {"--elevation", {"-30", "nan", "91", "''", "-0.001", "AUTO", "default"}},
        {"--threshold", {"-0.5", "2", "nan", "''"}},
        {"--model", {"bogus", "''", "GGX "}},
        {"--fresnel", {"bogus", "''"}},
        {"--geometry", {"bogus"}},
        {"--gl-backend", {"bogus"}},
        {"--gpu", {"-1", "1.5", "''", "1023", "x"}},  // 1023: within the registry, beyond any machine's EGL devices
        {"--tint", {"1,2", "1,2,3,4", "nan", "-1"}},
        {"--light", {"bogus", "area", "''"}},
        // A sphere has a size: zero or negative is no sphere; below 1e-100 the double twin's cap underflows.
        {"--light-radius", {"0", "-1", "-0", "nan", "inf", "''", "1e-101"}},
        {"--light-angle", {"0", "90", "91", "-1", "nan", "''", "1e-160"}},  // an angular radius in [1e-100, 90)
        {"--light-rings", {"33", "1.5", "-1", "automatic", "''"}},          // 0: the centre's rule
        {"--light-rule", {"bogus", "LTC", "''"}},
    };
    for (const auto& [flag, values] : numbers)
        for (const auto& v : values) cases.push_back({measure + flag + " " + v, 2, flag});
    cases.push_back({"render --size 32 --exposure 100 -o {d}/new.png", 2, "--exposure"});
    cases.push_back({"render --size 32 --exposure nan -o {d}/new.png", 2, "--exposure"});
    cases.push_back({"render --size 32 --view bogus -o {d}/new.png", 2, "--view"});
    cases.push_back({"measure --bogus-flag 1", 2, "--bogus-flag"});
    // A sphere that reaches the plane, at any angle of the sweep (its centre 10 cos 80 = 1.74 above it).
    cases.push_back({measure + "--light sphere --light-radius 2 --incidence 0:85:5", 2,
                     "--light-radius: a sphere of radius 2 at distance 10 and incidence 80 deg reaches the plane"});
    cases.push_back({"render --size 32 --light sphere --light-radius 10 -o {d}/existing.png", 2, "reaches the plane"});
    cases.push_back({measure + "--light disk --bumps explicit", 2, "--light disk: not with --bumps explicit"});
    cases.push_back({measure + "--light sphere --brdf {d}/ok.brdf", 2, "--light sphere: not with --brdf"});
    // Linearly transformed cosines are fitted to an isotropic analytic lobe: anything else is refused by name.
    cases.push_back(
        {measure + "--light disk --light-rule ltc --roughness-y 0.2", 2, "--light-rule ltc: the BRDF is anisotropic"});
    cases.push_back({measure + "--light sphere --light-rule ltc --model retro", 2,
                     "--light-rule ltc: a retroreflector's lobe is not about the mirror direction"});
    cases.push_back({"run {d}/tiny.toml --shard 1/2x -o {d}/sh", 2, "--shard"});
    cases.push_back({"run {d}/tiny.toml --shard 0/0 -o {d}/sh", 2, "--shard"});
    cases.push_back({"run ''", 2, "empty experiment name"});
    // A sweep takes what the flag takes: "auto" or a number in range; 0 is no longer a way to say automatic.
    cases.push_back({"run {d}/fov0.toml -o {d}/f", 2,
                     "fov0.toml:10: camera.fov: must be auto or a finite number in (0, 179] (got 0)"});
    cases.push_back({"run {d}/fovword.toml -o {d}/f", 2,
                     "fovword.toml:10: camera.fov: expected auto or a number in (0, 179] (got 'automatic')"});
    cases.push_back({"run {d}/elevword.toml -o {d}/f", 2,
                     "elevword.toml:10: sweep.range: must be auto or a finite number in [0, 90] (got -10)"});
    cases.push_back({"run {d}/tiny.toml --gl-backend bogus -o {d}/gb", 2, "bogus"});
    // `hilite brdf`'s own options (the flags it shares with measure: tests/brdf/test_brdf_cmd.cpp).
    cases.push_back({"brdf normalization --model phong", 2, "--model"});
    cases.push_back({"brdf normalization --roughness 0.1,-2", 2, "--roughness"});
    cases.push_back({"brdf normalization --model blinn --exponent nan", 2, "--exponent"});
    cases.push_back({"brdf strip --material gold", 2, "-o"});
    cases.push_back({"brdf strip --material gold --size 0 -o {d}/new.png", 2, "--size"});
    cases.push_back({"brdf strip --material gold -o /nonexistent-dir/x.png", 2, "-o"});
    cases.push_back({"brdf tabulate --model ggx --roughness 0.1 --roughness-y 0.3 -o {d}/new.binary", 2,
                     "--roughness-y: a MERL table is isotropic"});
    cases.push_back({"brdf tabulate --model ggx --roughness -1 -o {d}/new.binary", 2, "--roughness"});
    cases.push_back({"brdf tabulate --model ggx --roughness 0.1", 2, "-o: give the MERL .binary file to write"});
    cases.push_back({"brdf tabulate --model ggx --roughness 0.1 -o {d}", 2, "-o"});
    cases.push_back({"brdf tabulate --model ggx --roughness 0.1 -o {d}/no/such/dir/x.binary", 2, "-o"});
    cases.push_back({"brdf bounces --surface cubic", 2, "--surface"});
    return cases;
}

std::vector<Case> sceneCases(Scratch& s) {
    std::vector<Case> cases;
    const std::vector<std::pair<std::string, std::string>> files = {
        // text, the file:line[: key] expected
        {"[material]\nrougness = 0.1\n", ":2: material.rougness"},
        {"[material]\nroughness = -1\n", ":2"},
        {"[material]\nroughness = \"\"\n", ":2"},
        {"[material]\nroughness = nan\n", ":2"},
        {"[material]\nroughness = inf\n", ":2"},
        {"[material]\nroughness = [1, [2]]\n", ":2"},
        {"[material]\nroughness = { a = 1 }\n", ":2"},
        {"[material]\nmodel = \"bogus\"\n", ":2"},
        {"[materal]\nmodel = \"ggx\"\n", ":1: materal"},
        {"[light]\nincidence = 100\n", ":2"},
        {"[light]\nincidence = \"0:90:inf\"\n", ":2"},
        {"[light]\nroughness = 0.1\n", ":2: light.roughness"},
        {"[light]\nlight = \"sphere\"\nlight_radius = 9\nincidence = 60\n",
         ":3: light.light_radius: a sphere of radius 9"},
        {"[light]\nlight = \"disk\"\nlight_angle = 90\n",
         ":3: light.light_angle: must be a finite number in [1e-100, 90)"},
        {"[camera]\nsize = 0\n", ":2"},
        {"[camera]\nsize = \"16385\"\n", ":2"},
        {"[surface]\nbump_seed = 9007199254740993\n", ":2"},
        {"model = \"ggx\"\n", ":1"},
        {"[material\nmodel = 1\n", ":1"},
        {"[material]\nmodel = \"ggx\"\nmodel = \"phong\"\n", ":3"},
        {"[material]\nroughness = 0.1\n[material]\n", ":3"},
        {"\xff\xfe[material]\n", ":1"},
        {"[material]\nroughness = 1e400\n", ":2"},
        {"[material]\nfresnel = true\n", ":2"},
        {"[camera]\nfov = -1\n", ":2"},
        {"[camera]\nelevation = -30\n", ":2"},
        {"[camera]\nfov = 0\n", ":2: camera.fov"},
        {"[camera]\nfov = \"automatic\"\n", ":2: camera.fov"},
        {"[camera]\nelevation = \"Auto\"\n", ":2: camera.elevation"},
        {"[measurement]\nthreshold = 2\n", ":2"},
    };
    for (size_t i = 0; i < files.size(); ++i) {
        const std::string name = "scene" + std::to_string(i) + ".toml";
        s.write(name, files[i].first);
        cases.push_back(
            {"measure --scene {d}/" + name, 2, name + files[i].second});  // no --size: it overrides the file's
    }
    return cases;
}

std::vector<Case> brdfCases(Scratch& s) {
    std::vector<Case> cases;
    const std::vector<std::pair<std::string, std::string>> files = {
        {"", ".brdf"},
        {"analytic\n", ".brdf"},
        {"analytic\n::begin shader\nvec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y ) { return vec3(1.0); }\n",
         ".brdf"},
        {"analytic\n::begin parameters\nfloat a 0 1\n::end parameters\n::begin shader\n::end shader\n", ".brdf:"},
        {"analytic\n::begin parameters\nbogus a 0 1 0.5\n::end parameters\n::begin shader\nvec3 BRDF( vec3 L, vec3 V, "
         "vec3 N, vec3 X, vec3 Y ) { return vec3(a); }\n::end shader\n",
         ".brdf:"},
        {"analytic\n::begin parameters\nfloat a 1 0 0.5\n::end parameters\n::begin shader\nvec3 BRDF( vec3 L, vec3 V, "
         "vec3 N, vec3 X, vec3 Y ) { return vec3(a); }\n::end shader\n",
         ".brdf:"},
        {"analytic\n::begin parameters\nfloat a 0 1 nan\n::end parameters\n::begin shader\nvec3 BRDF( vec3 L, vec3 V, "
         "vec3 N, vec3 X, vec3 Y ) { return vec3(a); }\n::end shader\n",
         ".brdf:"},
        {"analytic\n::begin shader\nvoid main() {}\n::end shader\n", ".brdf:"},
        {"analytic\n::end shader\n", ".brdf:"},
        {"analytic\n::begin shader\n::begin shader\n::end shader\n", ".brdf:"},
    };
    for (size_t i = 0; i < files.size(); ++i) {
        const std::string name = "bad" + std::to_string(i) + ".brdf";
        s.write(name, files[i].first);
        cases.push_back({"measure --size 32 --brdf {d}/" + name, 2, name});
    }
    cases.push_back({"measure --size 32 --brdf {d}/ok.brdf --param alpha=nan", 2, "alpha"});
    cases.push_back({"measure --size 32 --brdf {d}/ok.brdf --param alpha=100", 2, "alpha"});
    cases.push_back({"measure --size 32 --brdf {d}/ok.brdf --param beta=1", 2, "beta"});
    cases.push_back({"measure --size 32 --brdf {d}/ok.brdf --param alpha", 2, "--param"});
    // The shader probe's child killed by a signal (a GL driver crash, made by a test hook): exit 2 naming the
    // file, the signal and the child's last line (was: an empty reason).
    cases.push_back({"measure --size 32 --brdf {d}/ok.brdf", 2,
                     "{d}/ok.brdf: the shader probe (a child process compiling and drawing the shader) was killed by "
                     "signal 11 (SIGSEGV, Segmentation fault): the GL driver crashed on this shader; its last output: "
                     "'test: simulated shader compiler crash'",
                     "HILITE_TEST_PROBE_SIGNAL=11"});
    cases.push_back(
        {"measure --size 32 --brdf {d}/ok.brdf", 2, "killed by signal 6 (SIGABRT", "HILITE_TEST_PROBE_SIGNAL=6"});
    cases.push_back({"render --size 32 --brdf {d}/ok.brdf -o {d}/new.png", 2, "{d}/ok.brdf: the shader probe",
                     "HILITE_TEST_PROBE_SIGNAL=6"});
    cases.push_back(
        {"run {d}/brdfexp.toml -o {d}/probe", 2, "{d}/ok.brdf: the shader probe", "HILITE_TEST_PROBE_SIGNAL=9"});
    return cases;
}

std::vector<Case> ndfCases(Scratch& s) {
    std::vector<Case> cases;
    const std::vector<std::pair<std::string, std::string>> files = {
        // text, the line expected
        {"", ""},
        {"theta_h_deg, D\n", ""},
        {"0, 1\n", ":1"},
        {"5, 1\n10, 1\n20, 1\n30, 0\n", ":1"},
        {"0, 1\n10, nan\n20, 1\n30, 0\n", ":2"},
        {"0, 1\n10, inf\n20, 1\n30, 0\n", ":2"},
        {"0, 1\n10, -1\n20, 1\n30, 0\n", ":2"},
        {"0, 1\n10, 1\n10, 1\n30, 0\n", ":3"},
        {"0, 1\n10, 1\n20, 1\n95, 0\n", ":4"},
        {"0, 1\n10, 1\n20\n30, 0\n", ":3"},
        {"0, 1\n10, 1\n20, 1, 3\n30, 0\n", ":3"},
        {"0, 0\n10, 0\n20, 0\n30, 0\n", ":4"},
        {"0,1e308\n10,1e308\n20,1e308\n30,1e308\n90,1e308\n", ":5"},
        {"0,1e-310\n10,1e-310\n20,1e-310\n30,1e-310\n90,0\n", ":5"},
        {"0, x\n10, 1\n20, 1\n30, 0\n", ":2"},  // a first line that is not numbers is the header
    };
    for (size_t i = 0; i < files.size(); ++i) {
        const std::string name = "ndf" + std::to_string(i) + ".csv";
        s.write(name, files[i].first);
        cases.push_back({"measure --size 32 --model tabulated --ndf-table {d}/" + name, 2, name + files[i].second});
        cases.push_back({"brdf normalization --model tabulated --ndf-table {d}/" + name, 2, name + files[i].second});
    }
    return cases;
}

std::vector<Case> pathCases() {
    return {
        // Inputs: regular files only, with a size cap.
        {"measure --size 32 --scene {d}/dir", 2, "'{d}/dir' is a directory"},
        {"measure --size 32 --scene /dev/zero", 2, "'/dev/zero' is a character device"},
        {"measure --size 32 --scene {d}/fifo", 2, "'{d}/fifo' is a FIFO"},
        {"measure --size 32 --scene {d}/missing.toml", 2, "{d}/missing.toml"},
        {"measure --size 32 --scene ''", 2, "--scene"},
        {"measure --size 32 --brdf /dev/zero", 2, "--brdf: '/dev/zero'"},
        {"measure --size 32 --brdf {d}/dir", 2, "--brdf: '{d}/dir' is a directory"},
        {"measure --size 32 --model tabulated --ndf-table /dev/zero", 2, "--ndf-table: '/dev/zero'"},
        {"measure --size 32 --model tabulated --ndf-table {d}/fifo", 2, "--ndf-table: '{d}/fifo' is a FIFO"},
        {"measure --size 32 --model tabulated --ndf-table {d}/dir", 2, "--ndf-table: '{d}/dir'"},
        {"run /dev/zero -o {d}/r", 2, "'/dev/zero' is a character device"},
        {"run {d}/dir -o {d}/r", 2, "is a directory"},
        {"run {d}/fifo -o {d}/r", 2, "is a FIFO"},
        {"run {d}/ok.toml -o {d}/r", 2, "ok.toml"},  // a scene is not an experiment
        // Outputs: only regular files are replaced; folders, devices, FIFOs and symlinks are refused.
        {"render --size 32 -o {d}/dir", 2, "-o: '{d}/dir' is a directory"},
        {"render --size 32 -o {d}/dir/", 2, "-o: '{d}/dir/' is a directory"},
        {"render --size 32 -o {d}/fifo", 2, "-o: '{d}/fifo' is a FIFO"},
        {"render --size 32 -o {d}/link.png", 2, "-o: '{d}/link.png' is a symlink"},
        {"render --size 32 -o {d}/devlink", 2, "-o: '{d}/devlink' is a symlink"},
        {"render --size 32 -o /dev/null", 2, "-o: '/dev/null' is a character device"},
        {"render --size 32 -o {d}/file.txt/x.png", 2, "-o: cannot write '{d}/file.txt/x.png'"},
        {"render --size 32 -o {d}/nodir/x.png", 2, "-o: cannot write '{d}/nodir/x.png'"},
        {"render --size 32 -o ''", 2, "--output"},
        {"render --size 32 -o {d}/new.png --float ''", 2, "--float"},
        {"run {d}/tiny.toml -o ''", 2, "--output"},
        {"merge {d}/dir -o ''", 2, "--output"},
        {"render --size 32 -o {d}/existing.png --float {d}/dir", 2, "--float: '{d}/dir' is a directory"},
        {"render --size 32 -o {d}/existing.png --float {d}/fifo", 2, "--float: '{d}/fifo' is a FIFO"},
        {"render --size 32 -o {d}/existing.png --float /dev/full", 2, "--float: '/dev/full'"},
        {"brdf strip --material gold -o {d}/dir", 2, "-o: '{d}/dir' is a directory"},
        {"brdf strip --material gold -o {d}/link.png", 2, "-o: '{d}/link.png' is a symlink"},
        {"run {d}/tiny.toml -o {d}/file.txt", 2, "-o: '{d}/file.txt' is a regular file, not a folder"},
        {"run {d}/tiny.toml -o {d}/file.txt/sub", 2, "-o: '{d}/file.txt' is a regular file"},
        {"run {d}/tiny.toml -o {d}/fifo", 2, "-o: '{d}/fifo' is a FIFO, not a folder"},
        {"run {d}/tiny.toml -o /dev/null", 2, "-o: '/dev/null' is a character device"},
        {"run {d}/tiny.toml -o {d}/runlink", 2, "-o: '{d}/runlink/results.jsonl' is a symlink"},
        {"merge {d}/dir -o {d}/runlink", 2, "holds no experiment.toml"},
        {"merge {d}/dir -o {d}/m", 2, "holds no experiment.toml"},
        {"merge {d}/missing -o {d}/m", 2, "holds no experiment.toml"},
    };
}

}  // namespace

TEST_CASE("cli::hostile every case is refused with one line naming the flag or file, and nothing changes") {
    Scratch s;
    std::vector<Case> cases = flagCases();
    for (auto* more : {&sceneCases, &brdfCases, &ndfCases}) {
        auto c = (*more)(s);
        cases.insert(cases.end(), c.begin(), c.end());
    }
    for (const auto& c : pathCases()) cases.push_back(c);
    MESSAGE(cases.size() << " hostile cases");
    CHECK(cases.size() >= 100);
    const auto before = snapshot(s.path);
    for (const Case& c : cases) {
        const std::string args = subst(c.args, s.path.string()), needle = subst(c.needle, s.path.string());
        CAPTURE(args);
        CAPTURE(c.env);
        const auto eq = c.env.find('=');
        if (!c.env.empty()) setenv(c.env.substr(0, eq).c_str(), c.env.substr(eq + 1).c_str(), 1);
        const Result r = hilite(args);
        if (!c.env.empty()) unsetenv(c.env.substr(0, eq).c_str());
        CAPTURE(r.out);
        CHECK(r.code == c.code);
        CHECK(lines(r.out) == 1);  // one line: no table begun, no partial output
        CHECK(r.out.find(needle) != std::string::npos);
        CHECK(r.out.find("internal error") == std::string::npos);
        CHECK(snapshot(s.path) == before);
    }
}

TEST_CASE("cli::hostile stdout that cannot be written is a failure, not exit 0") {
    CHECK(hilite("measure --size 32 --incidence 30 >/dev/full").code == 3);
    CHECK(hilite("measure --size 32 --incidence 30 --json >/dev/full").code == 3);
    CHECK(hilite("brdf albedo --model ggx --json >/dev/full").code == 3);
    CHECK(hilite("explain >/dev/full").code == 3);
    // Help and version too: text that never arrived is not a success.
    for (const char* cmd : {"--help", "--version", "measure --help", "render --help", "run --help", "merge --help",
                            "brdf albedo --help", "explain --help"}) {
        CAPTURE(cmd);
        const Result full = hilite(std::string(cmd) + " >/dev/full");
        CHECK(full.code == 3);  // (its message goes to /dev/full too: the helper joins stderr to stdout)
        CHECK(hilite(std::string(cmd) + " >/dev/null").code == 0);
    }
    CHECK(hilite("measure --size 32 --incidence 30 >/dev/null").code == 0);
}

TEST_CASE("cli::hostile automatic is the word auto, a number is taken literally") {
    TempDir d("hilite-auto");
    d.write("fov.toml", "[scene.camera]\nsize = \"32\"\n[[sweep]]\nkey = \"camera.fov\"\nvalues = [\"auto\", 20]\n");
    const Result run = hilite("run " + (d / "fov.toml") + " -o " + (d / "out"));
    CAPTURE(run.out);
    REQUIRE(run.code == 0);
    const std::string rows = slurp(d / "out/results.jsonl");
    CHECK(rows.find("\"framing\":\"automatic\"") != std::string::npos);  // auto: automatic framing
    CHECK(rows.find("\"framing\":\"fixed\"") != std::string::npos);      // 20: a fixed field of view
    CHECK(hilite("measure --size 32 --fov auto").code == 0);
    // Elevation 0 is the camera in the plane: a valid (black) view, said so in a warning; not the default.
    const Result grazing = hilite("render --size 16 --view photo --elevation 0 -o " + (d / "e0.png"));
    CHECK(grazing.code == 0);
    CHECK(grazing.out.find("warning: --elevation 0: the camera lies in the plane") != std::string::npos);
    const Result automatic = hilite("render --size 16 --view photo --elevation auto -o " + (d / "ea.png"));
    CHECK(automatic.code == 0);
    CHECK(automatic.out.find("warning") == std::string::npos);
}

TEST_CASE("cli::hostile an input larger than the cap is refused with the cap named") {
    Scratch s;
    std::string big(17u << 20, '#');
    s.write("huge.toml", big);
    const Result r = hilite("measure --size 32 --scene " + (s / "huge.toml"));
    CHECK(r.code == 2);
    CHECK(r.out.find("larger than 16 MiB") != std::string::npos);
}

namespace {

int sh(const std::string& cmd) {
    const int status = std::system((cmd + " >/dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::string> rowLines(const std::string& path) {
    std::vector<std::string> out;
    std::ifstream in(path);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

/// The "config" of each complete row of a results.jsonl.
std::vector<long> configsOf(const std::string& path) {
    std::vector<long> out;
    const std::string text = slurp(path);
    size_t start = 0;
    for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
        const std::string line = text.substr(start, end - start);
        const auto p = line.find("\"config\":");
        if (p != std::string::npos) out.push_back(std::atol(line.c_str() + p + 9));
    }
    return out;
}

const std::string kRamp = R"([experiment]
name = "ramp"
[scene.camera]
size = "64"
[[sweep]]
key = "material.model"
values = ["phong", "ggx"]
[[sweep]]
key = "light.incidence"
range = [0, 80, 1]
)";

}  // namespace

TEST_CASE("cli::hostile a disk filling up mid-run: non-zero exit, rows intact, --resume completes") {
    if (geteuid() != 0) {
        MESSAGE("skipped: mounting a tmpfs needs root");
        return;
    }
    TempDir d("hilite-full");
    d.write("ramp.toml", kRamp);
    const std::string mnt = d / "mnt";
    fs::create_directories(mnt);
    if (mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=120k") != 0) {
        MESSAGE("skipped: mount -t tmpfs is not available here");
        return;
    }
    struct Unmount {  // before the scratch folder is removed, whatever fails below
        std::string at;
        ~Unmount() { umount2(at.c_str(), MNT_DETACH); }
    } unmount{mnt};
    const Result full = hilite("run " + (d / "ramp.toml") + " -o " + mnt + "/r");
    CHECK(full.code == 3);
    CHECK(full.out.find("No space left on device") != std::string::npos);
    CHECK(full.out.find("--resume") != std::string::npos);
    const auto written = configsOf(mnt + "/r/results.jsonl");
    MESSAGE("rows on the full disk: " << written.size() << " of 162");
    CHECK(written.size() > 0);
    CHECK(written.size() < 162);
    for (size_t i = 0; i < written.size(); ++i) CHECK(written[i] == long(i));
    REQUIRE(mount("tmpfs", mnt.c_str(), "tmpfs", MS_REMOUNT, "size=4m") == 0);
    const Result resumed = hilite("run " + (d / "ramp.toml") + " -o " + mnt + "/r --resume");
    CHECK(resumed.code == 0);
    auto all = configsOf(mnt + "/r/results.jsonl");
    std::vector<long> sorted = all;
    std::sort(sorted.begin(), sorted.end());
    CHECK(all.size() == 162);
    CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());  // every row once
    CHECK(rowLines(mnt + "/r/results.csv").size() == 163);
    // A read-only filesystem: refused up front with the reason, not an internal error.
    REQUIRE(mount("tmpfs", mnt.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, "size=4m") == 0);
    const Result ro = hilite("run " + (d / "ramp.toml") + " -o " + mnt + "/r2");
    CHECK(ro.code == 2);
    CHECK(ro.out.find("Read-only file system") != std::string::npos);
    const Result roRender = hilite("render --size 32 -o " + mnt + "/x.png");
    CHECK(roRender.code == 2);
    CHECK(roRender.out.find("Read-only file system") != std::string::npos);
}

TEST_CASE("cli::hostile two runs into one folder: the second is refused at once, the first completes") {
    TempDir d("hilite-lock");
    d.write("ramp.toml", kRamp);
    const pid_t pid = fork();
    if (pid == 0) {
        execl(HILITE_EXE, HILITE_EXE, "run", (d / "ramp.toml").c_str(), "-o", (d / "r").c_str(), nullptr);
        _exit(127);
    }
    for (int i = 0; i < 5000 && !fs::exists(d / "r/results.jsonl"); ++i) usleep(1000);
    const Result second = hilite("run " + (d / "ramp.toml") + " -o " + (d / "r"));
    int status = 0;
    waitpid(pid, &status, 0);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
    if (configsOf(d / "r/results.jsonl").size() == 162 && second.code == 0) {
        MESSAGE("the first run finished before the second started: no overlap to test");
    } else {
        CHECK(second.code == 2);
        CHECK(second.out.find("is being written by another hilite run or merge") != std::string::npos);
    }
    CHECK(configsOf(d / "r/results.jsonl").size() == 162);
    // A merge into a folder that another process holds is refused the same way, and writes nothing there.
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "ramp.toml") + " --shard 1/40 -o " + (d / "s")) == 0);
    fs::create_directories(d.path / "m");
    const int fd = open((d / "m/.hilite.lock").c_str(), O_RDWR | O_CREAT, 0644);
    REQUIRE(fd >= 0);
    REQUIRE(flock(fd, LOCK_EX) == 0);
    const Result merge = hilite("merge " + (d / "s") + " -o " + (d / "m"));
    close(fd);
    CHECK(merge.code == 2);
    CHECK(merge.out.find("is being written by another hilite run or merge") != std::string::npos);
    CHECK_FALSE(fs::exists(d / "m/results.jsonl"));
}

TEST_CASE("cli::hostile --resume after editing the experiment is refused, naming what differs") {
    TempDir d("hilite-edit");
    d.write("tiny.toml", kSmall);
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "tiny.toml") + " -o " + (d / "r")) == 0);
    const std::string before = slurp(d / "r/results.jsonl");
    std::string edited = kSmall;
    edited.replace(edited.find("[0, 30, 60]"), 11, "[0, 45, 60]");
    d.write("tiny.toml", edited);
    const Result r = hilite("run " + (d / "tiny.toml") + " -o " + (d / "r") + " --resume");
    CHECK(r.code == 2);
    CHECK(lines(r.out) == 1);
    CHECK(
        r.out.find(
            "results.jsonl:2: row 2 (configuration 1) was measured with incidence = 30, the experiment now says 45") !=
        std::string::npos);
    CHECK(slurp(d / "r/results.jsonl") == before);
    // A material change shows in its column too; a comment or key order change is no change at all.
    d.write("tiny.toml", std::string("# a comment\n") + kSmall);
    CHECK(hilite("run " + (d / "tiny.toml") + " -o " + (d / "r") + " --resume").code == 0);
    d.write("other.toml", std::string(kSmall) + "[scene.material]\nroughness = 0.3\n");
    const Result m = hilite("run " + (d / "other.toml") + " -o " + (d / "r") + " --resume");
    CHECK(m.code == 2);
    CHECK(m.out.find("was measured with roughness = 0.1, the experiment now says 0.3") != std::string::npos);
}

TEST_CASE("cli::hostile merge of shards of different experiments is refused before anything is written") {
    TempDir d("hilite-mix");
    d.write("a.toml", kSmall);
    std::string other = kSmall;
    other.replace(other.find("[0, 30, 60]"), 11, "[0, 45, 60]");
    d.write("b.toml", other);
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "a.toml") + " --shard 1/2 -o " + (d / "s1")) == 0);
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "b.toml") + " --shard 2/2 -o " + (d / "s2")) == 0);
    const Result r = hilite("merge " + (d / "s1") + " " + (d / "s2") + " -o " + (d / "m"));
    CHECK(r.code == 2);
    CHECK(lines(r.out) == 1);
    CHECK(r.out.find("shards of different experiments") != std::string::npos);
    CHECK_FALSE(fs::exists(d / "m"));
    // Rows of another experiment copied into a shard are found by their fingerprint.
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "a.toml") + " --shard 2/2 -o " + (d / "s3")) == 0);
    const auto foreign = rowLines(d / "s2/results.jsonl");
    std::ofstream(d / "s3/results.jsonl", std::ios::trunc) << foreign.at(0) << "\n";
    const Result f = hilite("merge " + (d / "s1") + " " + (d / "s3") + " -o " + (d / "m"));
    CHECK(f.code == 2);
    CHECK(f.out.find("s3/results.jsonl:1: row 1 (configuration 1) was measured with incidence = 45") !=
          std::string::npos);
    CHECK_FALSE(fs::exists(d / "m"));
}

TEST_CASE("cli::hostile damaged rows on --resume and merge: file:line, exit 2, nothing rewritten") {
    TempDir d("hilite-damaged");
    d.write("tiny.toml", kSmall);
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "tiny.toml") + " -o " + (d / "r")) == 0);
    const auto rows = rowLines(d / "r/results.jsonl");
    REQUIRE(rows.size() == 3);
    const std::vector<std::pair<std::string, std::string>> damage = {
        {rows[0] + "\n{not json\n" + rows[2] + "\n", "results.jsonl:2: damaged row, not JSON"},
        {rows[0] + "\n[1, 2]\n", "results.jsonl:2: damaged row: expected a JSON object"},
        {rows[0] + "\n{\"config\": \"x\"}\n", "results.jsonl:2: config"},
        {rows[0] + "\n{\"config\": -1}\n", "results.jsonl:2: config"},
        {rows[0] + "\n{\"config\": 7}\n", "results.jsonl:2: row 2 (configuration 7)"},
        {rows[0] + "\n{\"config\": 1}\n", "results.jsonl:2: row 2 (configuration 1): fingerprint"},
        {rows[0] + "\n" + rows[0] + "\n", "configuration 0 appears twice"},
        {"\n", "results.jsonl:1: damaged row"},
    };
    for (const auto& entry : damage) {
        const auto& text = entry.first;
        const auto& needle = entry.second;  // not a structured binding: CAPTURE's lambda takes it (C++17)
        CAPTURE(needle);
        std::ofstream(d / "r/results.jsonl", std::ios::trunc) << text;
        const Result r = hilite("run " + (d / "tiny.toml") + " -o " + (d / "r") + " --resume");
        CHECK(r.code == 2);
        CHECK(lines(r.out) == 1);
        CHECK(r.out.find(needle) != std::string::npos);
        CHECK(r.out.find("internal error") == std::string::npos);
        CHECK(slurp(d / "r/results.jsonl") == text);
        const Result m = hilite("merge " + (d / "r") + " -o " + (d / "m"));
        CHECK(m.code == 2);
        CHECK(m.out.find("internal error") == std::string::npos);
        CHECK_FALSE(fs::exists(d / "m"));
    }
    // A torn last line (a kill mid-write) is no damage: dropped, and measured again.
    std::ofstream(d / "r/results.jsonl", std::ios::trunc) << rows[0] << "\n" << rows[1].substr(0, 30);
    CHECK(hilite("run " + (d / "tiny.toml") + " -o " + (d / "r") + " --resume").code == 0);
    CHECK(configsOf(d / "r/results.jsonl").size() == 3);
}
