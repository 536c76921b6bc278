#pragma once
// An experiment on a cluster: `hilite submit` writes a Slurm array job (one task per shard, each `hilite run
// --shard K/N --resume` into DIR/shards/K) and a merge job that depends on it (afterok: `hilite merge` of the
// shards into DIR, as a single run writes it), submits both with sbatch, and can follow them; `hilite status`
// reports a submitted folder's progress from the shard folders and the tasks' logs. Nothing here needs Slurm
// to be checked: every input is validated, and the programs it calls found, before anything is written.
//
// DIR/slurm/array.sbatch, merge.sbatch  the job scripts (paths quoted: a file's name is never shell code)
// DIR/slurm/submit.json                 what was submitted: experiment, shards, configurations, commands, job ids
// DIR/slurm/logs/shard-K.out|err        each array task's output; merge.out|err the merge's
// DIR/slurm/merge.rc                    the merge's exit status, written when it ends
// DIR/shards/K/                         shard K's result folder (results.jsonl, ...)

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace hilite::experiments {

struct SubmitOptions {
    std::string experiment;  ///< a file, or the name of one shipped in experiments/
    std::string out;         ///< the folder (required): merged rows, shards/ and slurm/ in it
    int shards = 0;          ///< array tasks, each a shard; in [1, configurations] (0 with resume: as submitted)
    std::string engine = "slurm";
    /// Passed to every sbatch call as given (argv, not a shell): "--partition=gpu", "--time=2:00:00", ...
    std::vector<std::string> sbatchArgs;
    std::string hilite;   ///< the program each task runs (absolute path of the hilite executable)
    std::string backend;  ///< --gl-backend for the tasks ("": theirs)
    bool dryRun = false;  ///< write the scripts and submit.json, submit nothing
    bool resume = false;  ///< resubmit only the shards with missing rows, then the merge
    std::string outName = "-o";
};

struct SubmitResult {
    std::string dir, name;
    size_t configurations = 0;
    int shards = 0;
    std::vector<int> submitted;      ///< the shards given to the array job (all, or the incomplete ones on resume)
    std::string arrayJob, mergeJob;  ///< job ids ("" on a dry run; arrayJob "" when no shard needed a task)
    std::vector<std::vector<std::string>> commands;  ///< the sbatch command lines, as run (or to run)
};

/// The allowed engines ("slurm").
const std::vector<std::string>& submitEngines();

/// Validates, writes the scripts and submit.json, and (unless dryRun) submits: InputError naming the flag for
/// bad input (no sbatch on PATH, shards out of range, a folder already submitted without --resume, or one whose
/// jobs are still queued), nothing written then; SystemError when sbatch itself fails.
SubmitResult submitExperiment(const SubmitOptions& o);

struct ShardStatus {
    int shard = 0;
    size_t rows = 0, expected = 0;
    std::string lastError;  ///< the last non-empty line of the task's error log ("" when none)
};

struct ClusterStatus {
    std::string dir, name;
    size_t configurations = 0, rows = 0;  ///< rows: in the shard folders
    int shards = 0;
    std::vector<ShardStatus> shard;  ///< one per shard, in order
    bool merged = false;             ///< the merge ended (merge.rc written)
    int mergeStatus = -1;            ///< its exit status
    size_t mergedRows = 0;           ///< rows in DIR/results.jsonl
    std::string arrayJob, mergeJob;
};

/// A submitted folder's progress (InputError when `dir` holds no submit.json).
ClusterStatus clusterStatus(const std::string& dir);

/// Follows a submitted folder until its merge ends or its jobs have left the queue without it (squeue), calling
/// `progress` every `pollSeconds`; returns the final status. A failed array leaves the merge pending forever
/// (its afterok can never be met): it is cancelled (scancel) and the status says which shards failed.
ClusterStatus waitForCluster(const std::string& dir, double pollSeconds,
                             const std::function<void(const ClusterStatus&)>& progress);

}  // namespace hilite::experiments
