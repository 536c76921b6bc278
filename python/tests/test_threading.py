"""The threading contract: one GL thread owned by the module; calls from any thread, run one at a time;
the GIL released while hilite works."""

import threading
import time

import numpy as np

SCENES = [dict(model="ggx", roughness=r, incidence=t, size=128) for r in (0.05, 0.2) for t in (10, 50, 80)]


def test_threads_get_serial_results(hilite):
    serial = [hilite.measure(**s)["aspect"] for s in SCENES]
    out = [None] * (4 * len(SCENES))
    errors = []

    def work(k):
        try:
            for i, s in enumerate(SCENES):
                out[k * len(SCENES) + i] = hilite.measure(**s)["aspect"]
        except Exception as e:  # noqa: BLE001
            errors.append(e)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert out == serial * 4


def test_gl_runs_on_one_thread_of_its_own(hilite):
    hilite.measure(size=64)
    tid = hilite._hilite.worker_thread_id()
    assert tid != ""
    t = threading.Thread(target=lambda: hilite.measure(size=64))
    t.start()
    t.join()
    assert hilite._hilite.worker_thread_id() == tid


def test_gil_released_while_measuring(hilite):
    hilite.measure(size=64)  # the context exists
    span = {}
    ticks = []
    started = threading.Event()

    def work():
        started.set()
        span["t0"] = time.perf_counter()
        hilite.measure(model="ggx", roughness=0.1, incidence=np.arange(0, 60.0, 2.0), size=512)
        span["t1"] = time.perf_counter()

    t = threading.Thread(target=work)
    t.start()
    started.wait()
    while t.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    t.join()
    inside = [x for x in ticks if span["t0"] < x < span["t1"]]
    # With the GIL held for the whole call this thread could not run until it returned: no tick inside.
    assert len(inside) >= 5, (len(inside), span["t1"] - span["t0"])


def test_errors_cross_threads(hilite):
    caught = []

    def work():
        try:
            hilite.measure(roughness=-1)
        except hilite.InputError as e:
            caught.append(str(e))

    t = threading.Thread(target=work)
    t.start()
    t.join()
    assert caught and caught[0].startswith("roughness:")
