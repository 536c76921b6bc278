// hilite submit (an experiment as a Slurm array job and a merge job) and hilite status (a submitted folder's
// progress): thin callers of experiments/cluster.hpp.

#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "hilite/experiments/cluster.hpp"

#include <unistd.h>

#include <climits>
#include <cstdio>
#include <iostream>
#include <memory>

namespace hilite::cli {

namespace {

struct SubmitFlags {
    experiments::SubmitOptions o;
    bool wait = false;
    double poll = 2.0;
};

/// The running executable's absolute path: what every task runs.
std::string selfExecutable() {
    char buf[PATH_MAX];
    const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
    return n > 0 ? std::string(buf, size_t(n)) : std::string();
}

void printStatus(const experiments::ClusterStatus& s) {
    std::printf(
        "%s: %zu of %zu rows in %d shards (%.0f%%); merge: %s\n", s.name.c_str(), s.rows, s.configurations, s.shards,
        s.configurations ? 100.0 * double(s.rows) / double(s.configurations) : 0.0,
        s.merged ? (s.mergeStatus == 0 ? ("done, " + std::to_string(s.mergedRows) + " rows in " + s.dir)
                                       : ("failed, exit " + std::to_string(s.mergeStatus) + " (slurm/logs/merge.err)"))
                       .c_str()
                 : ("not ended" + (s.mergeJob.empty() ? std::string() : " (job " + s.mergeJob + ")")).c_str());
    std::printf("%5s %9s %9s  %s\n", "shard", "rows", "expected", "state");
    for (const auto& sh : s.shard)
        std::printf("%5d %9zu %9zu  %s\n", sh.shard, sh.rows, sh.expected,
                    sh.rows == sh.expected ? "done"
                    : sh.lastError.empty() ? "incomplete"
                                           : ("incomplete; its log's last line: " + sh.lastError).c_str());
}

int runSubmit(SubmitFlags& f) {
    f.o.hilite = selfExecutable();
    const experiments::SubmitResult r = experiments::submitExperiment(f.o);
    if (f.o.dryRun) {
        std::cout << r.name << ": " << r.configurations << " configurations in " << r.shards << " shards; scripts in "
                  << r.dir << "/slurm (nothing submitted). To submit:\n";
        for (const auto& cmd : r.commands) {  // each word quoted where a shell would split or expand it
            std::string line;
            for (const auto& a : cmd) {
                const bool plain = !a.empty() && a.find_first_not_of(
                                                     "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                                     "0123456789_./=:%,+-@") == std::string::npos;
                std::string q = "'";
                for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
                line += (line.empty() ? "" : " ") + (plain ? a : q + "'");
            }
            std::cout << line << "\n";
        }
        return 0;
    }
    std::cout << r.name << ": " << r.configurations << " configurations in " << r.shards << " shards; "
              << (r.arrayJob.empty() ? std::string("no shard to run")
                                     : "array job " + r.arrayJob + " (" + std::to_string(r.submitted.size()) +
                                           (r.submitted.size() == 1 ? " task)" : " tasks)"))
              << ", merge job " << r.mergeJob << " after it -> " << r.dir << "\n";
    if (!f.wait) {
        std::cout << "follow it with: hilite status " << r.dir << "\n";
        return 0;
    }
    ProgressLine line;
    const auto s = experiments::waitForCluster(
        r.dir, f.poll, [&](const experiments::ClusterStatus& st) { line("rows", st.rows, st.configurations); });
    printStatus(s);
    if (s.merged) return s.mergeStatus == 0 ? 0 : 1;
    std::cout << "the array job ended with shards incomplete: the merge was cancelled; fix the cause (the logs in "
              << r.dir << "/slurm/logs) and resubmit the rest with hilite submit --resume -o " << r.dir << "\n";
    return 1;
}

}  // namespace

Action addSubmit(CLI::App& app) {
    auto f = std::make_shared<SubmitFlags>();
    app.add_option("experiment", f->o.experiment,
                   "experiment file, or the name of one shipped in experiments/ (with --resume: as submitted)");
    app.add_option("--shards", f->o.shards, "array tasks, each one shard of the configurations; [1, configurations]");
    app.add_option("-o,--output", f->o.out, "the folder: merged rows, shards/ and slurm/ in it")
        ->required()
        ->check(nonEmpty());
    app.add_option("--engine", f->o.engine, "slurm (the default)");
    app.add_option("--sbatch", f->o.sbatchArgs,
                   "an argument for every sbatch call, as given (repeatable): --sbatch=--partition=gpu "
                   "--sbatch=--time=2:00:00")
        ->allow_extra_args(false);
    app.add_option("--gl-backend", f->o.backend, "the tasks' GL backend: auto | osmesa | egl | egl-device");
    app.add_flag("--dry-run", f->o.dryRun,
                 "write the scripts and slurm/submit.json, print the sbatch commands, submit "
                 "nothing");
    app.add_flag(
        "--wait", f->wait,
        "follow the jobs (rows done of all, from the shard folders) until the merge ends; exit with its status "
        "(1 when a shard failed)");
    app.add_flag("--resume", f->o.resume, "resubmit only the shards with missing rows (each resumes), then the merge");
    app.footer("Example: hilite submit eccentricity --shards 4 -o results/ecc --sbatch=--time=10:00 --wait");
    return [f] { return runSubmit(*f); };
}

Action addStatus(CLI::App& app) {
    auto dir = std::make_shared<std::string>();
    app.add_option("folder", *dir, "a folder hilite submit wrote")->required()->check(nonEmpty());
    app.footer("Example: hilite status results/ecc");
    return [dir] {
        printStatus(experiments::clusterStatus(*dir));
        return 0;
    };
}

}  // namespace hilite::cli
