#!/usr/bin/env bash
# Latency of `penumbra serve` as the web viewer sees it: round trips of full
# and preview frames (a 2-degree orbit before each, as while dragging), the
# server's own prepare/render/encode times, a PNG for "save image", and how
# long a cheap request (GET /api/techniques) takes while another client's
# full frame is rendering. Medians of N frames; numbers go to stdout as a
# Markdown table. Needs python3 (standard library only).
# Usage: scripts/bench-web.sh [BUILD_DIR] [FRAMES] [SIZE]
set -euo pipefail
build=${1:-build}
frames=${2:-7}
size=${3:-512}
root=$(cd "$(dirname "$0")/.." && pwd)
data="$root/../shared/data"
[ -f "$data/engine_256x256x128_uint8.nhdr" ] || { echo "bench-web: needs $data/engine_256x256x128_uint8.nhdr" >&2; exit 1; }

log=$(mktemp)
"$build/penumbra" serve --port 0 --data "$data" > "$log" &
server=$!
trap 'kill $server 2>/dev/null; rm -f "$log"' EXIT
for _ in $(seq 100); do grep -q http "$log" && break; sleep 0.1; done
url=$(grep -o 'http://[0-9.:]*/' "$log")
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg); $frames frames per row; $(date -u +%F)"
echo

python3 - "$url" "$frames" "$size" <<'PY'
import json, math, statistics, sys, threading, time, urllib.request

url, frames, size = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])

def call(method, path, body=None):
    data = None if body is None else json.dumps(body).encode()
    req = urllib.request.Request(url + path, data=data, method=method, headers={"Content-Type": "application/json"})
    start = time.perf_counter()
    with urllib.request.urlopen(req) as r:
        payload = r.read()
        headers = dict(r.headers)
    return (time.perf_counter() - start) * 1000.0, headers, payload

def orbit(camera, degrees):
    # Rotates the eye about the target around z, like a horizontal drag.
    ex, ey, ez = (camera["eye"][i] - camera["target"][i] for i in range(3))
    a = math.radians(degrees)
    camera["eye"] = [camera["target"][0] + ex * math.cos(a) - ey * math.sin(a),
                     camera["target"][1] + ex * math.sin(a) + ey * math.cos(a), camera["target"][2] + ez]

_, _, body = call("POST", "api/sessions", {})
session = json.loads(body)
sid, scene = session["id"], session["scene"]

def frame_stats(technique, width, preview, fmt="jpeg"):
    scene["render"]["technique"] = technique
    scene["render"]["params"] = {"shadow_cache": True} if technique == "shadow-rays" else {}
    request = {"scene": scene, "width": width, "height": width, "preview": preview, "format": fmt,
               "quality": 70 if preview else 90}
    call("POST", f"api/sessions/{sid}/frame", request)  # builds the technique's structures
    trips, prepare, render, encode, sizes = [], [], [], [], []
    for _ in range(frames):
        orbit(scene["camera"], 2.0)
        ms, h, payload = call("POST", f"api/sessions/{sid}/frame", request)
        trips.append(ms)
        prepare.append(float(h["X-Prepare-Ms"]))
        render.append(float(h["X-Render-Ms"]))
        encode.append(float(h["X-Encode-Ms"]))
        sizes.append(len(payload))
    m = statistics.median
    return f"| {technique} | {'preview' if preview else 'full'} {width}² {fmt} | {m(trips):.0f} | {m(prepare):.1f} | {m(render):.0f} | {m(encode):.1f} | {m(sizes)/1024:.0f} |"

print("| technique | frame | round trip ms | prepare ms | render ms | encode ms | KiB |")
print("|---|---|---|---|---|---|---|")
for technique in ["emission-absorption", "phong", "shadow-rays", "filtered-sat"]:
    print(frame_stats(technique, size, False))
    print(frame_stats(technique, size // 2, True))
print(frame_stats("shadow-rays", size, False, "png"))

# A cheap request while a second session renders full frames back to back.
_, _, body = call("POST", "api/sessions", {})
other = json.loads(body)["id"]
idle = [call("GET", "api/techniques")[0] for _ in range(20)]
stop = False
def busy():
    request = {"scene": scene, "width": size, "height": size, "format": "jpeg"}
    while not stop:
        orbit(scene["camera"], 2.0)
        call("POST", f"api/sessions/{other}/frame", request)
worker = threading.Thread(target=busy)
worker.start()
time.sleep(0.3)
loaded = [call("GET", "api/techniques")[0] for _ in range(20)]
stop = True
worker.join()
print()
print(f"GET /api/techniques, median of 20: {statistics.median(idle):.1f} ms idle, "
      f"{statistics.median(loaded):.1f} ms while another client renders {size}² frames")
PY
