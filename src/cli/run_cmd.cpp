// `hilite run EXPERIMENT` and `hilite merge`: an experiment is a base scene plus sweep axes over any
// scene key; each configuration is measured and streamed to results.{jsonl,csv}; then plots, a contact
// sheet of photo views and summary.md are made from the rows. Shards run deterministic slices; merge
// joins them into what a single run writes.

#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "experiments/experiment.hpp"
#include "hilite/experiments/run.hpp"

#include <iostream>
#include <memory>

namespace hilite::cli {

namespace {

struct RunFlags {
    std::string experiment, out, shard;
    bool resume = false, check = false, fsyncEachRow = false;
    std::string backend;
};

int runExperiment(const RunFlags& f) {
    experiments::RunOptions o;
    experiments::parseShard(f.shard, o.shardK, o.shardN);
    o.experiment = f.experiment, o.out = f.out, o.resume = f.resume, o.backend = f.backend, o.check = f.check;
    o.fsyncEachRow = f.fsyncEachRow;
    o.progress = [](size_t done, size_t total, double seconds) { ProgressLine::show("", done, total, seconds); };
    const experiments::RunSummary s = experiments::runExperiment(o);
    if (f.check) {
        std::cout << s.name << ": " << s.configurations << " configurations, every one valid (checked only: nothing "
                  << "measured, nothing written to " << s.dir << ")\n";
        return 0;
    }
    if (!s.finalized) {
        std::cout << "shard " << o.shardK << "/" << o.shardN << ": " << s.measured << " rows in " << s.seconds
                  << " s -> " << s.dir << "/results.jsonl (join the shards with hilite merge)\n";
        return 0;
    }
    std::cout << s.name << ": " << s.configurations << " configurations (" << s.measured << " measured now) in "
              << s.seconds << " s -> " << s.dir << "/summary.md\n";
    return 0;
}

struct MergeFlags {
    std::vector<std::string> shards;
    std::string out, backend;
};

int runMerge(const MergeFlags& f) {
    const experiments::MergeSummary s = experiments::mergeShards(f.shards, f.out, f.backend);
    std::cout << "merged " << s.rows << " of " << s.expected << " rows from " << s.shards << " shards -> " << s.dir
              << "\n";
    return s.rows == s.expected ? 0 : 2;
}

}  // namespace

Action addRun(CLI::App& app) {
    auto f = std::make_shared<RunFlags>();
    app.add_option("experiment", f->experiment, "experiment file, or the name of one shipped in experiments/")
        ->required();
    app.add_option("-o,--output", f->out, "output folder (default results/<experiment name>)")->check(nonEmpty());
    app.add_flag("--resume", f->resume, "keep the completed rows already in the output folder and run the rest");
    app.add_option("--shard", f->shard, "run only configurations i with i mod N = K-1 (K/N, 1-based)");
    app.add_option("--gl-backend", f->backend, "auto | osmesa | egl | egl-device");
    app.add_flag("--fsync-each-row", f->fsyncEachRow,
                 "make each row durable (fsync) before the next is measured; by default rows are made durable "
                 "together, at most every 100 ms and at the end: a killed run loses no written row either way, a "
                 "power loss the rows of the last 100 ms, measured again by --resume");
    app.add_flag("--check", f->check,
                 "check the file, every configuration and the output folder as a run does first, then stop: nothing "
                 "measured or written");
    app.footer([] {
        std::string names;
        for (const std::string& n : experiments::shippedExperiments()) names += (names.empty() ? "" : ", ") + n;
        return "Shipped experiments: " + (names.empty() ? std::string("none found") : names) +
               "\nExample: hilite run eccentricity   (writes results/eccentricity/)";
    });
    return [f] { return runExperiment(*f); };
}

Action addMerge(CLI::App& app) {
    auto f = std::make_shared<MergeFlags>();
    app.add_option("shards", f->shards, "output folders of hilite run --shard K/N")->required();
    app.add_option("-o,--output", f->out, "folder for the merged results")->required()->check(nonEmpty());
    app.add_option("--gl-backend", f->backend, "auto | osmesa | egl | egl-device");
    app.footer("Example: hilite merge results/s1 results/s2 -o results/eccentricity");
    return [f] { return runMerge(*f); };
}

}  // namespace hilite::cli
