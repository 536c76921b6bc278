#!/usr/bin/env python3
"""ctest serve_api: `hilite serve`'s JSON API on a free loopback port, hostile requests included.

Every hostile request is answered 4xx with one line, nothing is read or written outside the page folder and
the results root, and the server is alive afterwards. 1000 concurrent requests finish in bounded time, each
answered 200 or 503 (the render queue is full), none 500. Usage: test_serve_api.py HILITE"""
import concurrent.futures
import http.client
import json
import os
import sys
import tempfile
import time
import urllib.parse

sys.path.insert(0, os.path.dirname(__file__))
from serve_fixture import measure_cli, request, server  # noqa: E402

HILITE = sys.argv[1]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


def one_line_4xx(status, text, what, code=None):
    check(400 <= status < 500 and (code is None or status == code), f"{what}: status {status} (want 4xx {code or ''})")
    check(text.endswith("\n") and text.count("\n") == 1 and text.startswith("hilite: "),
          f"{what}: not one 'hilite: ' line: {text!r}")


def raw_get(base, path, host=None):
    """A GET with the path sent byte for byte (no client normalises it), and the Host header `host` if given."""
    u = urllib.parse.urlparse(base)
    c = http.client.HTTPConnection(u.hostname, u.port, timeout=30)
    c.putrequest("GET", path, skip_host=host is not None, skip_accept_encoding=True)
    if host is not None:
        c.putheader("Host", host)
    c.endheaders()
    r = c.getresponse()
    body = r.read().decode("utf-8", "replace")
    c.close()
    return r.status, body


def snapshot(folder):
    out = {}
    for d, _, files in os.walk(folder):
        for f in files:
            p = os.path.join(d, f)
            out[p] = os.lstat(p).st_mtime_ns
    return out


def main():
    start = time.monotonic()
    outside = tempfile.mkdtemp(prefix="hilite-serve-outside-")
    secret = os.path.join(outside, "secret.txt")
    with open(secret, "w") as f:
        f.write("SECRET-OUTSIDE\n")
    with server(HILITE) as (base, root, proc):
        # A result folder of the right shape, a symlink out of the root, a file inside.
        os.makedirs(os.path.join(root, "run1"))
        with open(os.path.join(root, "run1", "results.jsonl"), "w") as f:
            f.write(json.dumps({"config": 0, "model": "ggx", "incidence_deg": 30, "aspect": 0.9}) + "\n")
        os.symlink(secret, os.path.join(root, "run1", "leak.png"))
        os.symlink(outside, os.path.join(root, "outside_dir"))
        before = snapshot(root), snapshot(outside)

        # --- the API answers
        status, text = request(base, "/api/registry")
        reg = json.loads(text)["parameters"]
        check(status == 200 and any(p["name"] == "roughness" and p["unit"] == "" and p["help"] for p in reg),
              "registry: roughness with help")
        check({"name", "default", "lo", "hi", "unit", "help", "allowed", "kind", "choices"} <= set(reg[0]),
              "registry: fields")
        values = {"model": "ggx", "roughness": "0.2", "incidence": "40", "size": "64"}
        status, text = request(base, "/api/measure", {"values": values})
        check(status == 200, f"measure: {status} {text[:200]}")
        row = json.loads(text)["rows"][0]
        cli = measure_cli(HILITE, values)
        check(set(row) == set(cli), f"measure: the CLI's row fields {set(row) ^ set(cli)}")
        check(abs(row["aspect"] - cli["aspect"]) <= 1e-6, f"measure: aspect {row['aspect']} vs CLI {cli['aspect']}")
        status, text = request(base, "/api/resolve", {"values": dict(values, incidence="0:80:40")})
        check(status == 200 and json.loads(text)["angles"] == [0, 40, 80] and json.loads(text)["effects"],
              f"resolve: {status} {text[:200]}")
        status, text = request(base, "/api/render", {"values": values})
        r = json.loads(text) if status == 200 else {}
        check(status == 200 and r["photo"]["png"] and r["measure"]["png"] and len(r["measure"]["ellipse"]) == 72,
              f"render: {status} {text[:200]}")
        check(sum(p is not None for p in r.get("measure", {}).get("ellipse", [])) > 36, "render: the ellipse is drawn")
        status, text = request(base, "/api/slice", {"curves": [{"label": "A", "values": {"model": "ggx"}}], "step": 2})
        check(status == 200 and json.loads(text)["points"], f"slice: {status} {text[:200]}")
        status, text = request(base, "/api/explain", {"values": {"model": "ggx", "roughness": 0.2}})
        import subprocess
        want = subprocess.run([HILITE, "explain", "--part", "scene", "--model", "ggx", "--roughness", "0.2"],
                              capture_output=True, text=True, check=True).stdout
        check(status == 200 and json.loads(text)["scene_toml"] == want, "explain: the scene TOML of explain --part scene")
        status, text = request(base, "/api/match", {"target": {"model": "ggx", "roughness": "0.1", "fresnel": "none"},
                                                    "values": {"model": "phong", "fresnel": "none"}})
        m = json.loads(text) if status == 200 else {}
        check(status == 200 and m["parameter"] == "exponent" and m["value"] > 1 and abs(m["target_major_deg"] - 7.42) < 0.1,
              f"match: {status} {text[:200]}")
        status, text = request(base, "/api/results")
        check(status == 200 and json.loads(text)["folders"] == ["run1"], f"results: {text[:200]}")
        status, text = request(base, "/api/results/run1")
        check(status == 200 and json.loads(text)["rows"][0]["aspect"] == 0.9, f"results/run1: {text[:200]}")
        status, text = request(base, "/")
        check(status == 200 and "<canvas" in text, "the page")
        status, text = request(base, "/results/run1/results.jsonl")
        check(status == 200 and '"aspect"' in text, "a file of the results root")

        # --- hostile requests: each 4xx with one line
        for path in ["/../../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/results/../../etc/passwd",
                     "/results/%2e%2e/%2e%2e/%2e%2e/etc/passwd", "/results//etc/passwd", "/results/%2fetc%2fpasswd",
                     "/results/run1/leak.png", "/results/outside_dir/secret.txt", "/api/results/..%2f..",
                     "/api/results/outside_dir", "/results/run1/%00x", "/%2e%2e%5c%2e%2e%5cetc/passwd",
                     "/nothing.html", "/results/run1/nope.png"]:
            status, text = raw_get(base, path)
            one_line_4xx(status, text, f"GET {path}")
            check("SECRET" not in text and "root:" not in text, f"GET {path}: leaked a file")
        status, text = raw_get(base, "/api/registry", host="evil.example:80")
        one_line_4xx(status, text, "a Host that is not this server's (DNS rebinding)", 403)
        status, text = raw_get(base, "/api/registry", host="localhost:1")
        check(status == 200, f"Host localhost: {status}")
        for what, body, raw in [
            ("bad JSON", None, b"{\"values\": "),
            ("NaN", None, b"{\"values\": {\"roughness\": NaN}}"),
            ("Infinity", None, b"{\"values\": {\"roughness\": 1e999}}"),
            ("nan text", {"values": {"roughness": "nan"}}, None),
            ("unknown key", {"values": {"model": "ggx"}, "colour": 1}, None),
            ("unknown parameter", {"values": {"roughnes": 0.1}}, None),
            ("out of range", {"values": {"roughness": -1}}, None),
            ("bad choice", {"values": {"model": "gg"}}, None),
            ("not an object", [1, 2], None),
            ("render too big", {"values": {"size": "4096"}}, None),
            ("a file outside", {"values": {"measured": "../../../etc/passwd"}}, None),
            ("an absolute file", {"values": {"brdf": secret}}, None),
            ("a symlinked file", {"values": {"measured": "run1/leak.png"}}, None),
        ]:
            status, text = request(base, "/api/measure", body, raw=raw)
            one_line_4xx(status, text, f"measure, {what}", 400)
        status, text = request(base, "/api/render", raw=b"{\"values\": {\"model\": \"" + b"x" * 200000 + b"\"}}")
        one_line_4xx(status, text, "a 200 KB body", 413)
        status, text = request(base, "/api/measure", {"values": {"roughness": -1}})
        check("--roughness" in text, f"the CLI's message names the flag: {text!r}")

        # --- 1000 concurrent requests, bounded in time and count
        t0 = time.monotonic()
        small = {"values": {"model": "ggx", "roughness": "0.3", "incidence": "20", "size": "32"}}

        def one(i):
            if i % 4 == 0:
                return request(base, "/api/registry")[0]
            return request(base, "/api/measure", small, timeout=120)[0]

        with concurrent.futures.ThreadPoolExecutor(max_workers=100) as pool:
            codes = list(pool.map(one, range(1000)))
        took = time.monotonic() - t0
        counts = {c: codes.count(c) for c in sorted(set(codes))}
        print(f"1000 concurrent requests (100 clients): {took:.1f} s, answers {counts}")
        check(set(codes) <= {200, 503}, f"1000 requests: only 200 and 503 expected, got {counts}")
        check(counts.get(200, 0) >= 250, f"1000 requests: every registry call and some measures answered: {counts}")
        check(took < 120, f"1000 requests took {took:.0f} s (the cap: 120)")
        status, _ = request(base, "/api/registry")
        check(status == 200 and proc.poll() is None, "the server is alive afterwards")
        after = snapshot(root), snapshot(outside)
        check(after == before, "nothing written in the results root or outside")
    os.remove(secret)
    os.rmdir(outside)
    print(f"serve_api: {len(failures)} failure(s), {time.monotonic() - start:.1f} s")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
