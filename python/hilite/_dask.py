"""hilite.run(..., client=): an experiment's configurations mapped over a dask.distributed client.

The client opens the result folder as ``hilite run`` does (every check, every .brdf probed, the lock, resumed
rows kept), sends chunks of configuration indices to the workers, and appends each row as its chunk comes back
(checked: a configuration of this run, not yet written, measured with the experiment's settings: its
fingerprint), made durable by group commit. Each worker process measures in process, with its own GL context
(the module's GL thread), the experiment loaded once per process. When every row is in, the folder is
rewritten in configuration order and finalized: the same rows, file and plots as a single run.

Workers read the experiment and its data files at the client's paths, from the client's working folder: on
several machines, a shared file system. A worker that sees other contents (an edited file) gives rows whose
fingerprints differ, and they are refused, never mixed in.
"""

import hashlib as _hashlib
import os as _os
import threading as _threading

from . import _hilite

_measurers = {}  # (experiment file, its contents' hash, backend) -> _hilite._Measurer, per worker process
_lock = _threading.Lock()  # one chunk at a time per process: the working folder is the process's


def _measure_chunk(experiment, backend, cwd, indices):
    """Runs on a worker: the rows (JSON lines) of configurations `indices` of `experiment`."""
    with _lock:
        here = _os.getcwd()
        _os.chdir(cwd)
        try:
            with open(experiment, "rb") as f:
                key = (experiment, _hashlib.sha256(f.read()).hexdigest(), backend)
            m = _measurers.get(key)
            if m is None:
                _measurers.clear()  # an older version of the file: its measurer is no longer needed
                m = _measurers[key] = _hilite._Measurer(experiment, backend)
            return m.measure(list(indices))
        finally:
            _os.chdir(here)


def _chunks(todo, size):
    return [todo[i:i + size] for i in range(0, len(todo), size)]


def run_on_client(client, experiment, out, resume, shard, backend, fsync_each_row, chunk_size):
    from distributed import as_completed  # Debian: python3-distributed

    run = _hilite._DistributedRun(experiment, out, resume, shard, backend, fsync_each_row)
    futures, where = [], run.dir
    try:
        todo = run.todo()
        if chunk_size is None:  # a few chunks per worker: balanced, and few round trips
            workers = max(1, len(client.scheduler_info().get("workers", {})))
            chunk_size = max(1, min(256, -(-len(todo) // (4 * workers))))
        chunks = _chunks(todo, chunk_size)
        n = len(chunks)
        futures = client.map(_measure_chunk, [run.experiment_path] * n, [backend] * n, [_os.getcwd()] * n,
                             chunks, pure=False)
        for future in as_completed(futures):
            run.append(future.result())
        return run.finish()
    except BaseException as e:
        client.cancel(futures)
        kept = run.close()  # the rows appended are durable, the folder unlocked
        if isinstance(e, _hilite.InputError) and kept:
            raise _hilite.InputError(f"{e} ({kept} rows measured now are kept in {where}: fix it and "
                                     "rerun with resume=True)") from e
        raise
