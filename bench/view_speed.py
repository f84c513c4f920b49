#!/usr/bin/python3
"""quiver view's speed and stability, measured over HTTP as the page uses it.

Starts `quiver view SCENE --width W --height H --threads T` and, on one
connection, times the API the page calls (bench/README.md, "quiver view"):

  coarse    a new view's first image (stage=coarse: 1/8 of each side, no
            anti-aliasing), request to last byte: median and worst over the
            views
  full      W x H without anti-aliasing (stage=full): views per second
            (one over the median request time)
  moves     --moves camera moves (a coarse frame each, every tenth also full),
            orbiting the initial look-at point; the server's resident memory
            (VmRSS) and thread count after the first 50 and after all of
            them: memory must stay flat and no thread be left behind

Usage: bench/view_speed.py [--quiver build/bin/quiver] [--width 640]
       [--height 360] [--threads 2] [--views 30] [--moves 1000] [SCENE...]
(no SCENE: the built-in scene). Prints one JSON object per scene.
"""
import argparse
import json
import math
import re
import signal
import statistics
import subprocess
import sys
import time
import urllib.request


def start_view(quiver, scene, width, height, threads):
    command = [quiver, "view"] + ([scene] if scene else []) + [
        "--width", str(width), "--height", str(height), "--threads", str(threads)]
    process = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 120
    for line in process.stderr:
        found = re.search(r"(http://\S+)", line)
        if found:
            return process, found.group(1)
        if time.time() > deadline:
            break
    process.kill()
    sys.exit(f"view_speed: {' '.join(command)} printed no URL")


def status_of(pid):
    fields = {}
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            key, _, value = line.partition(":")
            fields[key] = value.strip()
    return int(fields["VmRSS"].split()[0]) * 1024, int(fields["Threads"])


def orbit(view, angle):
    """The initial view turned by angle (radians) round its look-at point, about +y."""
    fx, fy, fz = (f - a for f, a in zip(view["from"], view["at"]))
    c, s = math.cos(angle), math.sin(angle)
    return [view["at"][0] + c * fx + s * fz, view["at"][1] + fy, view["at"][2] - s * fx + c * fz]


def frame_url(base, token, view, eye, width, height, stage):
    vector = lambda v: ",".join(repr(float(x)) for x in v)
    return (f"{base}/api/frame?token={token}&from={vector(eye)}&at={vector(view['at'])}&up={vector(view['up'])}"
            f"&fov={view['fov']!r}&width={width}&height={height}&stage={stage}")


def timed_get(url):
    start = time.perf_counter()
    with urllib.request.urlopen(url) as response:
        response.read()
    return (time.perf_counter() - start) * 1000.0


def measure(args, scene):
    process, url = start_view(args.quiver, scene, args.width, args.height, args.threads)
    try:
        base, token = url.split("/?token=")
        with urllib.request.urlopen(f"{base}/api/scene?token={token}") as response:
            info = json.load(response)
        view = info["view"]
        get = lambda angle, stage: timed_get(
            frame_url(base, token, view, orbit(view, angle), args.width, args.height, stage))
        get(0.0, "full")  # the threads started
        coarse = [get(0.01 * k, "coarse") for k in range(args.views)]
        full = [get(0.01 * k, "full") for k in range(args.views)]
        rss_warm = threads_warm = None
        for move in range(args.moves):
            get(0.003 * move, "coarse")
            if move % 10 == 9:
                get(0.003 * move, "full")
            if move == 49:
                rss_warm, threads_warm = status_of(process.pid)
        rss_end, threads_end = status_of(process.pid)
        return {
            "scene": scene or "built-in",
            "width": args.width,
            "height": args.height,
            "threads": args.threads,
            "coarse_ms_median": round(statistics.median(coarse), 2),
            "coarse_ms_worst": round(max(coarse), 2),
            "full_views_per_s": round(1000.0 / statistics.median(full), 2),
            "full_ms_median": round(statistics.median(full), 2),
            "moves": args.moves,
            "rss_after_50_moves_mb": round(rss_warm / 2**20, 1) if rss_warm else None,
            "rss_after_all_moves_mb": round(rss_end / 2**20, 1),
            "threads_after_50_moves": threads_warm,
            "threads_after_all_moves": threads_end,
        }
    finally:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quiver", default="build/bin/quiver")
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--views", type=int, default=30)
    parser.add_argument("--moves", type=int, default=1000)
    parser.add_argument("scenes", nargs="*")
    args = parser.parse_args()
    for scene in args.scenes or [""]:
        print(json.dumps(measure(args, scene)), flush=True)


if __name__ == "__main__":
    main()
