#!/usr/bin/python3
"""quiver-mpi under mpirun (docs/MPI.md), one case per ctest test:

  same-image SCENE  mpirun -np 1, 2 and 4 (different thread counts and SIMD
                    widths) write the same EXR bytes as `quiver render`; the
                    stats count every tile once and sum the rays of quiver's
  resume            rank 0 killed mid-render (SIGKILL): the job ends non-zero
                    with no image; --resume writes the same image, rendering
                    only the tiles the checkpoint lacked (stats)
  worker-killed     a worker killed mid-render: the job ends non-zero within
                    seconds, no image; the checkpoint resumes to the same image
  bad-input         a bad scene, a bad flag, a stale checkpoint, a checkpoint
                    naming an output under another spelling or a FIFO, under
                    -np 2: one error line, the right exit code, no output
  one-read          rank 0 alone reads the scene (textures and instanced
                    meshes): a worker given a scene path that does not exist
                    (mpirun's per-rank arguments) renders its share of the
                    same image; every rank reports its time to its first tile
  checkpoint-interval  the checkpoint is written once the interval has
                    passed, not before: one write (the last) under an hour's
                    interval, several under a microsecond's (stats)

Usage: app_mpi_render_test.py QUIVER QUIVER_MPI MPIRUN SOURCE_DIR CASE [ARG]
(run by ctest; exit 77 = skipped, saying why).
"""
import json
import os
import signal
import stat
import subprocess
import sys
import tempfile
import time

SKIP = 77
QUIVER, QUIVER_MPI, MPIRUN, SOURCE = sys.argv[1:5]
CASE = sys.argv[5]
ARG = sys.argv[6] if len(sys.argv) > 6 else None

ENV = dict(os.environ,
           OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_btl_vader_single_copy_mechanism="none",
           OMPI_MCA_rmaps_base_oversubscribe="1")

# (scene arguments, extra render flags): adaptive anti-aliasing with a
# rectangle area light (the built-in scene, with every AOV), refine with an
# area light, the SPD procedure's corner rays, adaptive on thin geometry.
SCENES = {
    "builtin-adaptive-aovs": ([], ["--width", "96", "--height", "72", "--aov", "depth,normal,id"]),
    "soft-shadows-refine": ([os.path.join(SOURCE, "io/examples/shadows_soft.toml")],
                            ["--width", "80", "--height", "60", "--aa", "refine:0.02:8"]),
    "tiny-spd-corners": ([os.path.join(SOURCE, "tests/data/scenes/tiny.nff")],
                         ["--width", "70", "--height", "50", "--preset", "spd"]),
    "thin-adaptive": ([os.path.join(SOURCE, "io/examples/adaptive_aa.toml")], ["--width", "100", "--height", "56"]),
}
# A render long enough to be killed in the middle: about 3 s on one rank of
# one thread, so the rank left alive cannot finish its tiles in the second
# mpirun takes to end the job after a rank dies.
SLOW = ([], ["--width", "256", "--height", "192", "--aa", "refine:0.005:16", "--threads", "1"])


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def mpirun(ranks):
    return [MPIRUN, "-np", str(ranks), "--oversubscribe", "--bind-to", "none"]


def run(command, timeout=120, cwd=None):
    done = subprocess.run(command, capture_output=True, text=True, env=ENV, timeout=timeout, cwd=cwd)
    return done


def same_bytes(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def quiver_reference(work, scene, flags, name="reference.exr"):
    out = os.path.join(work, name)
    stats = os.path.join(work, name + ".json")
    done = run([QUIVER, "render", *scene, *flags, "-o", out, "--stats", stats, "--quiet"])
    if done.returncode != 0:
        fail("quiver render failed (%d): %s" % (done.returncode, done.stderr))
    with open(stats) as f:
        return out, json.load(f)


def read_json(path):
    with open(path) as f:
        return json.load(f)


def case_same_image(work, scene_id):
    scene, flags = SCENES[scene_id]
    reference, reference_stats = quiver_reference(work, scene, flags + ["--threads", "2"])
    for ranks, extra in ((1, ["--threads", "2", "--simd", "scalar"]), (2, ["--threads", "1"]),
                         (4, ["--threads", "1", "--simd", "sse4"])):
        out = os.path.join(work, "mpi%d.exr" % ranks)
        stats = os.path.join(work, "mpi%d.json" % ranks)
        done = run(mpirun(ranks) + [QUIVER_MPI, *scene, *flags, *extra, "-o", out, "--stats", stats, "--quiet"])
        if done.returncode != 0:
            fail("-np %d %s exited %d:\n%s" % (ranks, " ".join(extra), done.returncode, done.stderr))
        if not same_bytes(out, reference):
            fail("-np %d %s: the image differs from quiver render's" % (ranks, " ".join(extra)))
        s = read_json(stats)
        m = s["mpi"]
        if m["ranks"] != ranks or len(m["per_rank"]) != ranks:
            fail("-np %d: stats report %d ranks" % (ranks, m["ranks"]))
        if m["tiles_rendered"] != m["tiles"] or m["tiles_resumed"] != 0:
            fail("-np %d: %d of %d tiles placed" % (ranks, m["tiles_rendered"], m["tiles"]))
        if sum(r["tiles"] for r in m["per_rank"]) != m["tiles"]:
            fail("-np %d: per-rank tiles do not add up" % ranks)
        # Every tile rendered once, unless given again at the end: then the rays are more.
        for kind in ("primary", "shadow", "reflection", "refraction"):
            mine, theirs = s["rays"][kind], reference_stats["rays"][kind]
            if (mine != theirs) if m["tiles_repeated"] == 0 else (mine < theirs):
                fail("-np %d: %s rays %d, quiver render's %d (%d repeated tiles)"
                     % (ranks, kind, mine, theirs, m["tiles_repeated"]))
            if sum(r["rays"][kind] for r in m["per_rank"]) != mine:
                fail("-np %d: per-rank %s rays do not add up" % (ranks, kind))
        if not 0 < m["efficiency"] <= 1:
            fail("-np %d: efficiency %s" % (ranks, m["efficiency"]))
        print("-np %d %s: same image; %d tiles over %s; efficiency %.2f"
              % (ranks, " ".join(extra), m["tiles"], [r["tiles"] for r in m["per_rank"]], m["efficiency"]))


def children(pid):
    """The processes whose parent is pid, with their MPI rank (Open MPI's or MPICH's variable)."""
    found = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open("/proc/%s/stat" % entry) as f:
                fields = f.read().rsplit(")", 1)[1].split()
            if int(fields[1]) != pid:
                continue
            with open("/proc/%s/environ" % entry, "rb") as f:
                env = dict(v.split(b"=", 1) for v in f.read().split(b"\0") if b"=" in v)
        except (OSError, IndexError, ValueError):
            continue
        rank = env.get(b"OMPI_COMM_WORLD_RANK", env.get(b"PMI_RANK"))
        if rank is not None:
            found[int(rank)] = int(entry)
    return found


def batches_in(checkpoint):
    try:
        return os.path.getsize(checkpoint)
    except OSError:
        return 0


def kill_mid_render(work, victim_rank, checkpoint, out):
    """Starts the slow render on 2 ranks, kills one once the checkpoint holds tiles; returns its exit code."""
    scene, flags = SLOW
    command = mpirun(2) + [QUIVER_MPI, *scene, *flags, "-o", out, "--checkpoint", checkpoint,
                           "--checkpoint-interval", "0.2", "--quiet"]
    job = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=ENV)
    try:
        deadline = time.time() + 60
        header = None
        while time.time() < deadline and job.poll() is None:
            size = batches_in(checkpoint)
            if header is None and size > 0:
                header = size
            if header is not None and size > header:
                break
            time.sleep(0.05)
        if job.poll() is not None:
            fail("the render ended (%d) before it could be killed:\n%s" % (job.returncode, job.stderr.read()))
        ranks = children(job.pid)
        if victim_rank not in ranks:
            fail("cannot find rank %d among mpirun's children: %s" % (victim_rank, ranks))
        os.kill(ranks[victim_rank], signal.SIGKILL)
        killed = time.time()
        try:
            _, stderr = job.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            fail("the job still runs 20 s after rank %d was killed" % victim_rank)
        print("rank %d killed: the job exited %d after %.1f s" % (victim_rank, job.returncode, time.time() - killed))
        if job.returncode == 0:
            fail("the job exited 0 after rank %d was killed:\n%s" % (victim_rank, stderr))
        if os.path.exists(out):
            fail("an image was written by a killed job")
        return stderr
    finally:
        if job.poll() is None:
            job.kill()
            job.wait()


def resume_and_compare(work, checkpoint, out, reference, reference_stats):
    stats = os.path.join(work, "resumed.json")
    scene, flags = SLOW
    done = run(mpirun(2) + [QUIVER_MPI, *scene, *flags, "-o", out, "--checkpoint", checkpoint, "--resume",
                            "--stats", stats, "--quiet"])
    if done.returncode != 0:
        fail("--resume exited %d:\n%s" % (done.returncode, done.stderr))
    if not same_bytes(out, reference):
        fail("the resumed image differs from quiver render's")
    m = read_json(stats)["mpi"]
    resumed, rendered, total = m["tiles_resumed"], m["tiles_rendered"], m["tiles"]
    print("resumed %d of %d tiles from the checkpoint, rendered %d" % (resumed, total, rendered))
    if resumed <= 0 or resumed >= total:
        fail("the checkpoint held %d of %d tiles" % (resumed, total))
    if rendered != total - resumed:
        fail("rendered %d tiles, not the %d missing" % (rendered, total - resumed))
    rays = read_json(stats)["rays"]["primary"]
    if m["tiles_repeated"] == 0 and rays >= reference_stats["rays"]["primary"]:
        fail("the resumed render traced %d primary rays, the whole image %d" % (rays, reference_stats["rays"]["primary"]))
    if os.path.exists(checkpoint):
        fail("the checkpoint is left after a finished render")


def case_killed(work, victim_rank):
    scene, flags = SLOW
    reference, reference_stats = quiver_reference(work, scene, flags)
    out = os.path.join(work, "killed.exr")
    checkpoint = os.path.join(work, "killed.checkpoint")
    kill_mid_render(work, victim_rank, checkpoint, out)
    resume_and_compare(work, checkpoint, out, reference, reference_stats)


def expect_one_error(done, code, pattern, what):
    lines = [l for l in done.stderr.splitlines() if l.startswith("quiver-mpi:")]
    if done.returncode != code:
        fail("%s: exit %d, expected %d:\n%s" % (what, done.returncode, code, done.stderr))
    if len(lines) != 1 or pattern not in lines[0]:
        fail("%s: expected one 'quiver-mpi: ...%s...' line, found:\n%s" % (what, pattern, done.stderr))
    print("%s: exit %d, %s" % (what, code, lines[0]))


def case_bad_input(work):
    out = os.path.join(work, "bad.png")
    bad = os.path.join(work, "bad.nff")
    with open(bad, "w") as f:
        f.write("v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 8\ns 0 0 zero 1\n")
    done = run(mpirun(2) + [QUIVER_MPI, bad, "-o", out])
    expect_one_error(done, 1, "bad.nff:8:", "a bad scene")
    done = run(mpirun(2) + [QUIVER_MPI, os.path.join(work, "missing.nff"), "-o", out])
    expect_one_error(done, 1, "missing.nff", "a missing scene")
    done = run(mpirun(2) + [QUIVER_MPI, "--aa", "sometimes", "-o", out])
    expect_one_error(done, 2, "--aa", "a bad --aa")
    done = run(mpirun(2) + [QUIVER_MPI, "--no-such-flag", "-o", out])
    expect_one_error(done, 2, "no-such-flag", "an unknown flag")
    # A checkpoint of another render (another seed) is refused.
    checkpoint = os.path.join(work, "stale.checkpoint")
    scene, flags = SLOW
    kill_mid_render(work, 0, checkpoint, out)
    done = run(mpirun(2) + [QUIVER_MPI, *scene, *flags, "--seed", "7", "-o", out, "--checkpoint", checkpoint,
                            "--resume"])
    expect_one_error(done, 1, "another render", "a stale checkpoint")
    done = run(mpirun(2) + [QUIVER_MPI, "-o", out, "--checkpoint", os.path.join(work, "none"), "--resume"])
    expect_one_error(done, 1, "nothing to resume", "--resume without a checkpoint")
    # The checkpoint under a second spelling of an output, or a FIFO: refused, nothing written or removed.
    tiny = ["--width", "8", "--height", "6"]
    done = run(mpirun(2) + [QUIVER_MPI, *tiny, "-o", "n1.png", "--checkpoint", "./n1.png"], cwd=work)
    expect_one_error(done, 2, "name the same file", "a checkpoint naming the image")
    done = run(mpirun(2) + [QUIVER_MPI, *tiny, "-o", "n2.png", "--stats", "n3.json", "--checkpoint", "./n3.json"],
               cwd=work)
    expect_one_error(done, 2, "name the same file", "a checkpoint naming the stats")
    fifo = os.path.join(work, "pipe.checkpoint")
    os.mkfifo(fifo)
    for resume in ([], ["--resume"]):
        done = run(mpirun(2) + [QUIVER_MPI, *tiny, "-o", "n4.png", "--checkpoint", fifo, *resume], timeout=60)
        expect_one_error(done, 2, "must name a regular file", "a FIFO checkpoint" + (" resumed" if resume else ""))
    if not os.path.exists(fifo) or not stat.S_ISFIFO(os.stat(fifo).st_mode):
        fail("the FIFO checkpoint was replaced or removed")
    os.remove(fifo)
    if os.path.exists(out):
        fail("an image was written")
    left = sorted(f for f in os.listdir(work) if f not in ("bad.nff", "stale.checkpoint"))
    if left:
        fail("files left behind: %s" % left)


def case_one_read(work):
    flags = ["--width", "64", "--height", "48", "--threads", "1", "--aov", "normal,id"]
    for scene in ("io/examples/textures.toml", "io/examples/instances.toml"):
        path = os.path.join(SOURCE, scene)
        reference, _ = quiver_reference(work, [path], flags)
        out, stats = os.path.join(work, "one_read.exr"), os.path.join(work, "one_read.json")
        missing = os.path.join(work, "no_such_scene.toml")
        rank0 = ["-np", "1", QUIVER_MPI, path, *flags, "-o", out, "--stats", stats, "--quiet"]
        workers = ["-np", "2", QUIVER_MPI, missing, *flags, "-o", out, "--quiet"]
        done = run([MPIRUN, "--oversubscribe", "--bind-to", "none", *rank0, ":", *workers])
        if done.returncode != 0:
            fail("%s with workers given a missing scene exited %d:\n%s" % (scene, done.returncode, done.stderr))
        if not same_bytes(out, reference):
            fail("%s: the image differs from quiver render's" % scene)
        per_rank = read_json(stats)["mpi"]["per_rank"]
        if len(per_rank) != 3 or not all(r["start_ms"] > 0 for r in per_rank):
            fail("%s: expected 3 ranks each with a time to its first tile: %s" % (scene, per_rank))


def case_checkpoint_interval(work):
    scene, flags = SCENES["builtin-adaptive-aovs"]
    writes = {}
    # Zero (the open end of the range) and one past the bound (a day) are
    # refused; the bound itself and a microsecond are run below.
    for refused, what in (("86400.001", "an interval past a day"), ("0", "a zero interval")):
        done = run(mpirun(2) + [QUIVER_MPI, *scene, *flags, "-o", os.path.join(work, "past.exr"), "--quiet",
                                "--checkpoint-interval", refused])
        expect_one_error(done, 2, "--checkpoint-interval: expected seconds in (0, 86400]", what)
    for interval in ("86400", "0.000001"):
        out, stats = os.path.join(work, "interval.exr"), os.path.join(work, "interval.json")
        done = run(mpirun(2) + [QUIVER_MPI, *scene, *flags, "-o", out, "--stats", stats, "--quiet",
                                "--checkpoint", os.path.join(work, "interval.checkpoint"),
                                "--checkpoint-interval", interval])
        if done.returncode != 0:
            fail("--checkpoint-interval %s exited %d:\n%s" % (interval, done.returncode, done.stderr))
        m = read_json(stats)["mpi"]
        writes[interval] = m["checkpoints"]
        print("--checkpoint-interval %s: %d checkpoint writes for %d tiles" % (interval, m["checkpoints"], m["tiles"]))
    if writes["86400"] != 1:
        fail("a day's interval wrote the checkpoint %d times in a short render (expected once, at the end)"
             % writes["86400"])
    if writes["0.000001"] < 2:
        fail("a microsecond's interval wrote the checkpoint %d times" % writes["0.000001"])


def main():
    if not os.access(MPIRUN, os.X_OK):
        print("SKIP: no mpirun (%s)" % MPIRUN)
        return SKIP
    with tempfile.TemporaryDirectory(prefix="quiver_mpi_test") as work:
        if CASE == "same-image":
            case_same_image(work, ARG)
        elif CASE == "resume":
            case_killed(work, 0)
        elif CASE == "worker-killed":
            case_killed(work, 1)
        elif CASE == "bad-input":
            case_bad_input(work)
        elif CASE == "one-read":
            case_one_read(work)
        elif CASE == "checkpoint-interval":
            case_checkpoint_interval(work)
        else:
            fail("unknown case " + CASE)
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
