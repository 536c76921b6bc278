"""A `hilite serve` started on a free loopback port with a temporary results root, stopped in every case.

Used by test_serve_api.py and test_serve_browser.py (plain scripts: ctest runs them with /usr/bin/python3)."""
import contextlib
import json
import os
import shutil
import signal
import subprocess
import tempfile
import time
import urllib.error
import urllib.request


@contextlib.contextmanager
def server(hilite, results=None, extra=()):
    """Yields (base_url, results_root, process). The process is stopped (SIGTERM, then SIGKILL) on the way out,
    whatever happened; the temporary folder is removed."""
    tmp = tempfile.mkdtemp(prefix="hilite-serve-test-")
    root = results or os.path.join(tmp, "results")
    os.makedirs(root, exist_ok=True)
    env = dict(os.environ, MESA_SHADER_CACHE_DISABLE="true")
    proc = subprocess.Popen([os.path.abspath(hilite), "serve", "--port", "0", "--results", root, *extra], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env, cwd=tmp)
    try:
        line = proc.stdout.readline().strip()
        if not line.startswith("serving http://"):
            proc.kill()
            raise RuntimeError(f"hilite serve did not start: {line!r} {proc.stderr.read()}")
        base = line.split(" ", 1)[1].rstrip("/")
        yield base, root, proc
    finally:
        if proc.poll() is None:
            proc.send_signal(signal.SIGTERM)
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
        shutil.rmtree(tmp, ignore_errors=True)
        err = proc.stderr.read()
        if "Sanitizer" in err or "runtime error:" in err:  # the sanitized build's findings in the server
            raise AssertionError("hilite serve: " + err[-4000:])


def request(base, path, body=None, raw=None, method=None, timeout=60):
    """(status, body text) of a request; body: JSON-encoded, raw: bytes sent as they are."""
    data = raw if raw is not None else (json.dumps(body).encode() if body is not None else None)
    req = urllib.request.Request(base + path, data=data, method=method or ("POST" if data is not None else "GET"),
                                 headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=timeout) as r:
            return r.status, r.read().decode("utf-8", "replace")
    except urllib.error.HTTPError as e:
        return e.code, e.read().decode("utf-8", "replace")


def measure_cli(hilite, values):
    """`hilite measure --json` for a page's values (parameter -> text): the row."""
    args = [hilite, "measure", "--json"]
    for name, text in values.items():
        args += ["--" + name.replace("_", "-"), str(text)]
    out = subprocess.run(args, check=True, capture_output=True, text=True,
                         env=dict(os.environ, MESA_SHADER_CACHE_DISABLE="true")).stdout
    return json.loads(out.splitlines()[0])


def wait_for(predicate, timeout, what):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        value = predicate()
        if value:
            return value
        time.sleep(0.02)
    raise AssertionError(f"timed out after {timeout} s waiting for {what}")
