#!/usr/bin/python3
"""Predicts quiver-mpi's parallel efficiency at 2 to 1,024 ranks from a real
render's per-tile times and a measured message latency and bandwidth, for
dynamic scheduling (quiver-mpi's: costliest tiles first, batches shrinking
to one tile, 3 batches plus 2 tiles per thread in flight, rank 0 rendering
too and placing every result) against static round-robin (tile i on rank
i mod N, no messages until the end). docs/MPI.md has the figures.

  bench/mpi_simulate.py --network net.json --frame NAME=STATS.json ... \
      [--check-costs STATS.json --check STATS.json ...] [--cores 2] [--chart bench/mpi_scaling.png]

STATS.json: `quiver-mpi --stats S --tile-times` output (tile_ms, tile_size,
width, height, load_ms, build_ms, memory_bytes). net.json: build/bin/quiver_mpi_pingpong's
line. --check: measured runs (their mpi.ranks, threads, render_ms): the
simulator replays each with the tile times of --check-costs (a 1-rank run of
the same render), ranks sharing --cores cores, and prints predicted against
measured render time. Not modelled: tiles given again at the end (rank 0's
threads and idle ranks repeating a tile still out elsewhere).

Efficiency is T(1 rank) / (N x T(N ranks)), each rank one thread, over the
render (the tiles) and, in the second figure, over the whole run (rank 0's
start: the scene read and built, its view, fingerprint, film and checkpoint;
the scene broadcast to the other ranks; the cost estimate; then the
tiles). The broadcast is modelled as a binomial tree: ceil(log2 N) rounds,
each one message of the built scene (its stores and BVHs, memory_bytes) at
the measured latency and the bandwidth of the largest messages measured.
"""
import argparse
import heapq
import json
import math
import os
import sys

POLL_S = 0.001            # quiver-mpi's communicating threads poll this often


def load_frame(path):
    with open(path) as f:
        s = json.load(f)
    if "tile_ms" not in s:
        sys.exit("%s: no tile_ms (render it with quiver-mpi --stats FILE --tile-times)" % path)
    costs = [float(ms) / 1000.0 for ms in s["tile_ms"] if ms is not None]
    estimates = s.get("tile_cost_estimate") or costs
    estimates = [e for e, ms in zip(estimates, s["tile_ms"]) if ms is not None]
    return {"costs": costs, "estimates": estimates, "width": s["width"], "height": s["height"], "tile_size": s.get("tile_size", 16),
            "startup_s": startup_s(s),
            "scene_bytes": s["memory_bytes"]["scene"] + s["memory_bytes"]["acceleration"],
            # The cost estimate's work, all ranks together (each estimates 1/N of the tiles).
            "estimate_s": s["mpi"]["estimate_ms"] * s["mpi"]["ranks"] / 1000.0,
            "tile_bytes": 3 * 4 * s.get("tile_size", 16) ** 2}


def startup_s(stats):
    """Rank 0's time before its tiles, the cost estimate apart (counted on its own): the rank's start_ms
    (reading and building the scene, its default view, fingerprint, film and checkpoint), else the
    stats' load and build alone."""
    per_rank = stats["mpi"].get("per_rank", [{}])
    if "start_ms" in per_rank[0]:
        return (per_rank[0]["start_ms"] - stats["mpi"]["estimate_ms"]) / 1000.0
    return (stats["load_ms"] + stats["build_ms"]) / 1000.0


def message_s(net, nbytes):
    return net["latency_s"] + nbytes / net["bandwidth_b_s"]


def broadcast_s(net, nbytes, ranks):
    """Rank 0's built scene to every rank: a binomial tree's rounds, each at the largest messages' bandwidth."""
    if ranks == 1:
        return 0.0
    return math.ceil(math.log2(ranks)) * (net["latency_s"] + nbytes / net["copy_b_s"])


def simulate_static(costs, ranks, net, tile_bytes, speed=1.0):
    """Round-robin: each rank renders its tiles back to back, sends them as it goes."""
    busy = [0.0] * ranks
    for i, c in enumerate(costs):
        busy[i % ranks] += c / speed
    last = max(busy)
    return last + (message_s(net, tile_bytes) if ranks > 1 else 0.0)


def simulate_dynamic(costs, estimates, ranks, net, tile_bytes, threads=1, speed=1.0):
    """An event simulation of quiver-mpi's coordinator (app/mpi_render.cpp, app/tile_schedule.cpp):
    tiles ordered and batched by their estimated cost, rendered in their measured time."""
    n = len(costs)
    waiting = sorted(range(n), key=lambda t: -estimates[t])
    waiting.reverse()  # pop() from the end gives the costliest
    waiting_cost = [sum(estimates)]
    done = [False] * n
    done_count = 0
    outstanding = [0] * ranks
    queue = [[] for _ in range(ranks)]  # each worker's tiles, in arrival order
    free_threads = [threads] * ranks
    events = []  # (time, seq, kind, rank, tile or tiles)
    seq = [0]

    def push(time, kind, rank, payload):
        seq[0] += 1
        heapq.heappush(events, (time, seq[0], kind, rank, payload))

    def batch_size():
        return min(16, max(1, len(waiting) // (8 * ranks)))

    def take(max_tiles):
        limit = min(batch_size(), max_tiles, len(waiting))
        budget = waiting_cost[0] / (8.0 * ranks)
        tiles, cost = [], 0.0
        while len(tiles) < limit:
            e = estimates[waiting[-1]]
            if tiles and cost + e > budget:
                break
            cost += e
            tiles.append(waiting.pop())
        waiting_cost[0] -= cost
        return tiles

    def refill(rank, now):
        target = 3 * batch_size() + 2 * threads
        while waiting and outstanding[rank] + batch_size() <= target:
            tiles = take(target - outstanding[rank])
            k = len(tiles)
            outstanding[rank] += k
            # Sent now; seen by the worker after the latency and its next poll.
            push(now + message_s(net, 4 * k) + POLL_S / 2, "work", rank, tiles)

    def start_tiles(rank, now):
        while free_threads[rank] > 0:
            if rank == 0:
                if not waiting:
                    return
                t = take(1)[0]
                outstanding[0] += 1
            else:
                if not queue[rank]:
                    return
                t = queue[rank].pop(0)
            free_threads[rank] -= 1
            push(now + costs[t] / speed, "tile", rank, t)

    now = 0.0
    start_tiles(0, now)
    for r in range(1, ranks):
        refill(r, now)
    coordinator_free = 0.0  # rank 0's communicating thread, one message at a time
    finish = 0.0
    while events:
        now, _, kind, rank, payload = heapq.heappop(events)
        if kind == "work":
            queue[rank].extend(payload)
            start_tiles(rank, now)
        elif kind == "tile":
            free_threads[rank] += 1
            if rank == 0:
                if not done[payload]:
                    done[payload] = True
                    done_count += 1
                    finish = max(finish, now)
                outstanding[0] -= 1
                start_tiles(0, now)
            else:
                start_tiles(rank, now)
                # The result: sent at the worker's next poll, placed by rank 0's thread.
                arrive = now + POLL_S / 2 + message_s(net, tile_bytes)
                push(arrive, "result", rank, payload)
        elif kind == "result":
            placed = max(now, coordinator_free) + tile_bytes / net["copy_b_s"]
            coordinator_free = placed
            outstanding[rank] -= 1
            if not done[payload]:
                done[payload] = True
                done_count += 1
                finish = max(finish, placed)
            refill(rank, placed)
    assert done_count == n, (done_count, n)
    return finish


def efficiency(t1, tn, ranks):
    return t1 / (ranks * tn)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--network", required=True)
    parser.add_argument("--frame", action="append", default=[], help="NAME=STATS.json")
    parser.add_argument("--check", action="append", default=[])
    parser.add_argument("--check-costs", help="the tile times the --check runs are replayed with (a 1-rank run)")
    parser.add_argument("--cores", type=int, default=2)
    parser.add_argument("--ranks", default="1,2,4,8,16,32,64,128,256,512,1024")
    parser.add_argument("--chart")
    parser.add_argument("--json")
    args = parser.parse_args()
    with open(args.network) as f:
        measured = json.load(f)
    net = {"latency_s": measured["latency_us"] * 1e-6,
           "bandwidth_b_s": measured["bandwidth_mb_s"]["3072"] * 1e6,
           "copy_b_s": max(measured["bandwidth_mb_s"].values()) * 1e6}
    print("network: latency %.2f us, %.0f MB/s for a 3 KiB tile" % (measured["latency_us"],
                                                                    net["bandwidth_b_s"] / 1e6))
    frames = []
    for spec in args.frame:
        name, path = spec.split("=", 1)
        frames.append((name, load_frame(path)))
    ranks_list = [int(r) for r in args.ranks.split(",")]
    results = {}
    print("%-24s %6s %10s %10s %10s %12s" % ("frame", "ranks", "dynamic", "static", "dyn+start", "T(N) dyn s"))
    for name, frame in frames:
        costs = frame["costs"]
        t1 = sum(costs)
        start, estimate = frame["startup_s"], frame["estimate_s"]
        rows = []
        for n in ranks_list:
            dyn = simulate_dynamic(costs, frame["estimates"], n, net, frame["tile_bytes"])
            sta = simulate_static(costs, n, net, frame["tile_bytes"])
            # Against one plain quiver process: rank 0 reads and builds the scene and broadcasts it
            # (no faster for more ranks), they share the estimate, then render.
            started = start + broadcast_s(net, frame["scene_bytes"], n)
            whole = (start + t1) / (n * (started + estimate / n + dyn))
            rows.append({"ranks": n, "dynamic": efficiency(t1, dyn, n), "static": efficiency(t1, sta, n),
                         "dynamic_with_startup": whole, "render_s": dyn})
            print("%-24s %6d %10.3f %10.3f %10.3f %12.3f" % (name, n, rows[-1]["dynamic"], rows[-1]["static"],
                                                          whole, dyn))
        results[name] = {"tiles": len(costs), "t1_s": t1, "startup_s": frame["startup_s"], "rows": rows}

    for path in args.check:
        with open(path) as f:
            s = json.load(f)
        m = s["mpi"]
        frame = load_frame(args.check_costs)
        n = m["ranks"]
        threads = m["per_rank"][0]["threads"]
        speed = min(1.0, args.cores / float(n * threads))
        predicted = simulate_dynamic(frame["costs"], frame["estimates"], n, net, frame["tile_bytes"], threads, speed)
        print("check %-40s ranks %d x %d threads: render %.2f s measured, %.2f s predicted (%+.1f%%)"
              % (os.path.basename(path), n, threads, m["render_ms"] / 1000.0, predicted,
                 100.0 * (predicted - m["render_ms"] / 1000.0) / (m["render_ms"] / 1000.0)))
        results.setdefault("checks", []).append({"stats": os.path.basename(path), "ranks": n, "threads": threads,
                                                 "measured_s": m["render_ms"] / 1000.0, "predicted_s": predicted})

    if args.json:
        with open(args.json, "w") as f:
            json.dump({"network": measured, "frames": results}, f, indent=1)
    if args.chart:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(8, 5))
        for i, (name, frame) in enumerate(frames):
            rows = results[name]["rows"]
            xs = [r["ranks"] for r in rows]
            line, = ax.plot(xs, [r["dynamic"] for r in rows], marker="o", label=name + " dynamic")
            ax.plot(xs, [r["static"] for r in rows], marker="x", linestyle="--", color=line.get_color(),
                    label=name + " static")
        ax.set_xscale("log", base=2)
        ax.set_ylim(0, 1.05)
        ax.axhline(0.9, color="grey", linewidth=0.5)
        ax.set_xlabel("ranks (1 thread each)")
        ax.set_ylabel("predicted parallel efficiency (render)")
        ax.set_title("quiver-mpi: dynamic against static round-robin tiles")
        ax.legend(fontsize=7, ncol=2)
        fig.tight_layout()
        fig.savefig(args.chart, dpi=100)
        print("chart:", args.chart)


if __name__ == "__main__":
    main()
