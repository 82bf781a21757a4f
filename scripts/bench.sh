#!/usr/bin/env bash
# Runs the benchmarks behind every speed claim in the docs and writes docs/benchmarks.md: the
# machine, the date, the commit, and per row the command, the median and the range of the
# repetitions, the goal, and the ratio to a peer (Blender's lattice modifier, PyGeM's algorithm
# in numpy) where the peer is installed. The README's short table (between the
# "bench:readme" markers) is rewritten from the same numbers.
#
#   scripts/bench.sh [--quick] [--repetitions N] [--no-build] [--build DIR] [--out FILE] [--no-readme]
#
#   --quick          3 repetitions instead of 9 (a rough page in a few minutes)
#   --repetitions N  N repetitions of every benchmark, CLI run and Python call
#   --no-build       use the binaries in the build directory as they are (rows whose program is
#                    missing say "not built")
#   --build DIR      build directory (default build/, or $FFDKIT_BUILD_DIR)
#   --out FILE       the page to write (default docs/benchmarks.md)
#   --no-readme      leave README.md alone
#
# Each Google Benchmark program runs once with a filter naming its rows, with
# --benchmark_repetitions; a row's median and range are over the repetitions' wall times. The
# CLI row times `ffdkit-cli deform --timings` on a 1000 x 1000 binary PLY grid it writes to a
# temporary folder (one warm-up run first, not counted). Numbers from a machine busy with other
# work run slower and spread more: the script prints the load average it saw before and after.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FFDKIT_BUILD_DIR:-$root/build}"
reps=9
do_build=1
out="$root/docs/benchmarks.md"
readme="$root/README.md"
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) reps=3; shift ;;
    --repetitions) reps="$2"; shift 2 ;;
    --no-build) do_build=0; shift ;;
    --build) build="$(cd "$2" && pwd)"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --no-readme) readme=""; shift ;;
    *) echo "bench.sh: unknown argument '$1' (see the comment at the top of scripts/bench.sh)" >&2; exit 2 ;;
  esac
done
case "$reps" in '' | *[!0-9]* | 0) echo "bench.sh: --repetitions needs a positive integer, got '$reps'" >&2; exit 2 ;; esac

# The commit the programs are built from, taken before the build (the tree may move while the
# benchmarks run).
commit="$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
if [ -n "$(git -C "$root" status --porcelain --untracked-files=no 2>/dev/null)" ]; then commit="$commit (with uncommitted changes)"; fi

if [ "$do_build" = 1 ]; then
  FFDKIT_BUILD_DIR="$build" "$root/scripts/build.sh" --target bench_ffd --target bench_meshio \
    --target bench_geometry_quaternion --target bench_interaction --target bench_guarded_drag --target bench_animation --target bench_exporters \
    --target bench_geometry_cardinal --target bench_geometry_curvenet --target bench_geometry_g3 \
    --target bench_geometry_polyhedron --target ffdkit-cli --target ffdkit_python
fi

# The Python with numpy (Debian's, which scripts/setup-deps.sh installs it into).
python=python3
for candidate in /usr/bin/python3 python3; do
  if "$candidate" -c 'import numpy' >/dev/null 2>&1; then python="$candidate"; break; fi
done

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
load_before="$(cut -d' ' -f1-3 /proc/loadavg)"
echo "bench.sh: $reps repetitions; load average before: $load_before"
# Whether other work ran beside the benchmarks: the machine's busy CPU time (/proc/stat) less this
# script's own and its children's (/proc/$$/stat), over the run. (The load average cannot tell:
# the benchmarks' own threads raise it.)
machine_cpu() { awk '/^cpu / { print $2 + $3 + $4 + $7 + $8 + $9 }' /proc/stat; }
own_cpu() { awk '{ print $14 + $15 + $16 + $17 }' "/proc/$$/stat"; }
machine_before="$(machine_cpu)"
own_before="$(own_cpu)"
start_ns="$(date +%s%N)"

# ---- Google Benchmark programs -------------------------------------------------------------
# gbench NAME BINARY FILTER [ENV...]: runs BINARY with FILTER, all repetitions kept, into NAME.json.
gbench() {
  local name="$1" program="$2" binary="$build/bench/$2" filter="$3"
  shift 3
  if [ ! -x "$binary" ]; then
    echo "bench.sh: $binary not built; its rows say so" >&2
    return 0
  fi
  echo "bench.sh: $program ($filter)"
  env OMP_WAIT_POLICY=passive "$@" "$binary" --benchmark_filter="$filter" --benchmark_repetitions="$reps" \
    --benchmark_out="$work/$name.json" --benchmark_out_format=json >/dev/null 2>"$work/$name.err" ||
    { echo "bench.sh: $program failed:" >&2; tail -5 "$work/$name.err" >&2; }
}
kernel='^BM_Deform/points:1000000/lattice:4x4x4/basis:(bspline3|bernstein)/'
update='^BM_Update/points:1000000/lattice:8x8x8/basis:bspline3/moved:(corner|interior)[^/]*/update:(exact|delta)/process_time'
embed='^BM_EmbedBox/points:1000000/lattice:4x4x4/basis:bspline3/|^BM_EmbedNewton/points:1000000/lattice:[^/]*/rest:[a-z]*/process_time'
gbench ffd ffd/bench_ffd "$kernel|$update|$embed"
gbench interaction app/bench_interaction '^BM_DragStep/points:1M/|^BM_DragFirstStep/points:1M/|^BM_Hover/points:1M/|^BM_UndoDrag/points:10M/'
gbench guarded app/bench_guarded_drag '^BM_GuardedDragStep/guard:(off|keep-volume|keep-centre)/reads:(none|view)/'
gbench animation app/bench_animation '^BM_(Animation|Playback)Frame'
gbench meshio meshio/bench_meshio '^BM_(Read|Write)Mesh/format:[a-z]+/vertices:1000000/'
gbench quaternion geometry/quaternion/bench_geometry_quaternion '^BM_QiFit_points_164_segments_6$' OMP_NUM_THREADS=1
# Every benchmark of the generated-geometry topics and of the glTF export (the page's second table).
gbench all_cardinal geometry/cardinal/bench_geometry_cardinal '.'
gbench all_curvenet geometry/curvenet/bench_geometry_curvenet '.'
gbench all_g3 geometry/g3/bench_geometry_g3 '.'
gbench all_polyhedron geometry/polyhedron/bench_geometry_polyhedron '.'
gbench all_quaternion geometry/quaternion/bench_geometry_quaternion '.'
gbench all_exporters exporters/bench_exporters '.'

# ---- End to end: ffdkit-cli deform on a 1,000,000-vertex binary PLY ---------------------------
cli="$build/app/cli/ffdkit-cli"
cli_command="OMP_WAIT_POLICY=passive $cli deform -w widgets/examples/fig6-8.json grid.ply -o out.ply --fit --set push-front=0.2 --set turn-back=0.3 --timings"
if [ -x "$cli" ] && "$python" -c 'import numpy' >/dev/null 2>&1; then
  echo "bench.sh: ffdkit-cli deform, 1,000,000 vertices"
  "$python" - "$work/grid.ply" <<'PY'
import sys
import numpy as np
side = 1000
i, j = np.meshgrid(np.arange(side), np.arange(side), indexing="ij")
points = np.stack([j / (side - 1), i / (side - 1), 0.05 * np.sin(6.0 * j / side)], axis=-1).reshape(-1, 3).astype("<f4")
a = (i[:-1, :-1] * side + j[:-1, :-1]).ravel()
quads = np.stack([a, a + 1, a + side + 1, a + side], axis=-1)
tris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
faces = np.zeros(len(tris), dtype=[("n", "u1"), ("v", "<i4", (3,))])
faces["n"], faces["v"] = 3, tris
with open(sys.argv[1], "wb") as f:
    f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
             "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
             % (len(points), len(tris))).encode())
    f.write(points.tobytes())
    f.write(faces.tobytes())
PY
  for run in $(seq 0 "$reps"); do
    (cd "$work" && OMP_WAIT_POLICY=passive "$cli" deform -w "$root/widgets/examples/fig6-8.json" grid.ply -o out.ply \
      --fit --set push-front=0.2 --set turn-back=0.3 --timings) >"$work/cli.$run.txt" 2>&1 ||
      { echo "bench.sh: ffdkit-cli failed:" >&2; tail -5 "$work/cli.$run.txt" >&2; break; }
  done
  rm -f "$work/cli.0.txt"  # the warm-up run
fi

# ---- Python: ffdkit.pygem.FFD against PyGeM's algorithm in numpy -----------------------------
python_command="PYTHONPATH=$build/python OMP_WAIT_POLICY=passive $python bench/python/bench_pygem.py --repeat $((2 * reps + 1)) --samples"
if [ -d "$build/python/ffdkit" ]; then
  echo "bench.sh: bench/python/bench_pygem.py"
  PYTHONPATH="$build/python" OMP_WAIT_POLICY=passive "$python" "$root/bench/python/bench_pygem.py" \
    --repeat $((2 * reps + 1)) --samples >"$work/python.txt" 2>&1 ||
    { echo "bench.sh: bench_pygem.py failed:" >&2; tail -5 "$work/python.txt" >&2; }
fi

# ---- Blender's lattice modifier, when Blender is installed -----------------------------------
blender_command="bench/compare/blender_lattice.sh $build $reps 1"
if command -v blender >/dev/null 2>&1 && [ -x "$build/bench/ffd/bench_ffd" ]; then
  echo "bench.sh: Blender's lattice modifier"
  "$root/bench/compare/blender_lattice.sh" "$build" "$reps" 1 >"$work/blender.txt" 2>&1 ||
    { echo "bench.sh: blender_lattice.sh failed:" >&2; tail -5 "$work/blender.txt" >&2; }
fi

load_after="$(cut -d' ' -f1-3 /proc/loadavg)"
other_cores="$(awk -v m="$(( $(machine_cpu) - machine_before ))" -v o="$(( $(own_cpu) - own_before ))" \
  -v hz="$(getconf CLK_TCK)" -v ns="$(( $(date +%s%N) - start_ns ))" \
  'BEGIN { v = (m - o) / hz / (ns / 1e9); printf "%.2f", v < 0 ? 0 : v }')"
echo "bench.sh: load average after: $load_after; other work beside the benchmarks: $other_cores cores on average"

# ---- The page ---------------------------------------------------------------------------------
cpu="$(lscpu 2>/dev/null | sed -n 's/^Model name:[[:space:]]*//p' | head -1)"
memory="$(awk '/^MemTotal/ { printf "%.1f GiB", $2 / 1048576 }' /proc/meminfo)"
FFDKIT_BENCH_WORK="$work" FFDKIT_BENCH_BUILD="$build" FFDKIT_BENCH_REPS="$reps" \
FFDKIT_BENCH_CPU="${cpu:-unknown}" FFDKIT_BENCH_CORES="$(nproc)" FFDKIT_BENCH_MEMORY="$memory" \
FFDKIT_BENCH_COMMIT="$commit" FFDKIT_BENCH_DATE="$(date -u +%Y-%m-%d)" FFDKIT_BENCH_OS="$(uname -sr)" \
FFDKIT_BENCH_CLI="$cli_command" FFDKIT_BENCH_PYTHON="$python_command" FFDKIT_BENCH_BLENDER="$blender_command" \
FFDKIT_BENCH_LOAD_BEFORE="$load_before" FFDKIT_BENCH_LOAD_AFTER="$load_after" FFDKIT_BENCH_OTHER_CORES="$other_cores" \
FFDKIT_BENCH_ROOT="$root" python3 - "$out" "$readme" <<'PY'
import json, os, re, statistics, sys

env = os.environ
work, root, build, reps = env["FFDKIT_BENCH_WORK"], env["FFDKIT_BENCH_ROOT"], env["FFDKIT_BENCH_BUILD"], int(env["FFDKIT_BENCH_REPS"])
out_path, readme_path = sys.argv[1], sys.argv[2]
rel_build = os.path.relpath(build, root)
UNIT = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


def gbench_runs(name):
    """{benchmark name: [wall ms per repetition]} from NAME.json (None when it did not run)."""
    path = os.path.join(work, name + ".json")
    if not os.path.exists(path):
        return None
    runs = {}
    with open(path) as f:
        for b in json.load(f).get("benchmarks", []):
            if b.get("run_type") == "iteration" and "error_occurred" not in b:
                runs.setdefault(b["run_name"], []).append(b["real_time"] * UNIT[b["time_unit"]])
    return runs


def find(runs, pattern):
    if runs is None:
        return None, "not built"
    names = [n for n in runs if re.search(pattern, n)]
    if not names:
        return None, "did not run"
    return runs[names[0]], names[0]


GBENCH = {k: gbench_runs(k) for k in ("ffd", "interaction", "guarded", "animation", "meshio", "quaternion")}
PROGRAM = {"ffd": "bench/ffd/bench_ffd", "interaction": "bench/app/bench_interaction", "guarded": "bench/app/bench_guarded_drag",
           "animation": "bench/app/bench_animation",
           "meshio": "bench/meshio/bench_meshio", "quaternion": "bench/geometry/quaternion/bench_geometry_quaternion"}

# CLI: "timings (ms): read 29.7, build scene 0.1, embed 3.7, deform 5.3, write 22.9, total 63.5"
cli = {}
for run in range(1, reps + 1):
    p = os.path.join(work, "cli.%d.txt" % run)
    if not os.path.exists(p):
        continue
    m = re.search(r"timings \(ms\):(.*)", open(p).read())
    if m:
        for item in m.group(1).split(","):
            key, _, value = item.strip().rpartition(" ")
            cli.setdefault(key, []).append(float(value))

python_rows = {}
p = os.path.join(work, "python.txt")
if os.path.exists(p):
    for line in open(p):
        m = re.match(r"samples ms \[(.*)\]: (.*)", line)
        if m:
            python_rows[m.group(1)] = [float(v) for v in m.group(2).split()]

blender = None
p = os.path.join(work, "blender.txt")
if os.path.exists(p):
    m = re.search(r"Blender lattice modifier\s+([\d.]+)", open(p).read())
    if m:
        blender = float(m.group(1))


def fmt_range(samples):
    return "%s-%s" % (fmt(min(samples))[:-3], fmt(max(samples)))


def fmt(ms):
    if ms is None:
        return "-"
    if ms >= 100:
        return "%.0f ms" % ms
    if ms >= 10:
        return "%.1f ms" % ms
    if ms >= 1:
        return "%.2f ms" % ms
    return "%.3f ms" % ms


rows = []  # dicts: what, samples, note, command, goal, limit, peer, readme


def add(what, samples, note, command, goal="", limit=None, peer="", readme=None):
    rows.append(dict(what=what, samples=samples, note=note, command=command, goal=goal, limit=limit, peer=peer,
                     readme=readme))


def gb(group, pattern, what, goal="", limit=None, peer="", readme=None, env_prefix="OMP_WAIT_POLICY=passive"):
    samples, name = find(GBENCH[group], pattern)
    if samples is None:
        command = "%s %s/%s --benchmark_filter='%s' --benchmark_repetitions=%d" % (
            env_prefix, rel_build, PROGRAM[group], pattern, reps)
        add(what, None, name, command, goal, limit, peer, readme)
        return None
    command = "%s %s/%s --benchmark_filter='^%s$' --benchmark_repetitions=%d" % (
        env_prefix, rel_build, PROGRAM[group], re.escape(name), reps)
    add(what, samples, "", command, goal, limit, peer, readme)
    return samples


blender_note = "not installed" if blender is None else None


def blender_ratio(samples):
    if blender is None or samples is None:
        return "Blender: not installed" if blender is None else "-"
    return "%.3f x Blender (%s)" % (statistics.median(samples) / blender, fmt(blender))


K = "BM_Deform/points:1000000/lattice:4x4x4/basis:"
d = find(GBENCH["ffd"], "^" + K + "bspline3/process_time")[0]
gb("ffd", "^" + K + "bspline3/process_time", "full update, 1M points, 4x4x4 cubic B-spline lattice",
   "<= 4 ms", 4.0, blender_ratio(d), readme="FFD of 1M points, 4x4x4 cubic lattice")
s = find(GBENCH["ffd"], "^" + K + "bspline3/precision:single")[0]
gb("ffd", "^" + K + "bspline3/precision:single", "the same in single precision (float32 displacements, as Blender)",
   "<= 0.035 x Blender", None, blender_ratio(s), readme="the same, single precision")
gb("ffd", "^" + K + "bernstein/process_time", "full update, 1M points, 4x4x4 Bernstein lattice", "<= 4 ms", 4.0)
U = "^BM_Update/points:1000000/lattice:8x8x8/basis:bspline3/moved:"
gb("ffd", U + r"interior\(3,3,3\)/update:exact/process_time", "one control point moved, 8x8x8 cubic, interior (3,3,3), exact update", "<= 4 ms", 4.0)
gb("ffd", U + r"interior\(3,3,3\)/update:delta/process_time", "the same, delta update (what a drag step uses)", "<= 4 ms", 4.0)
gb("ffd", U + r"corner\(0,0,0\)/update:exact/process_time", "one control point moved, 8x8x8 cubic, corner (0,0,0), exact update")
B = "^BM_EmbedBox/points:1000000/lattice:4x4x4/basis:bspline3/"
gb("ffd", B + "inside:100%", "closed-form (box) embedding, 1M points, 4x4x4 cubic, all inside", "<= 5 ms", 5.0,
   readme="embedding 1M points in a box lattice")
gb("ffd", B + "inside:75%", "the same, a quarter of the points outside", "<= 5 ms", 5.0)
N = "^BM_EmbedNewton/points:1000000/lattice:"
gb("ffd", N + "4x4x4/rest:user/process_time", "Newton embedding, 1M points, user-shaped 4x4x4 rest lattice", "<= 100 ms", 100.0,
   readme="Newton embedding, 1M points, user-shaped lattice")
gb("ffd", N + "3x8x4/rest:cylindrical/process_time", "Newton embedding, 1M points, cylindrical 3x8x4 (EFFD)", "<= 100 ms", 100.0)
gb("interaction", "^BM_DragStep/points:1M/", "one drag step of a point widget, 1M-vertex sphere (model, deformer, view data; no GL)",
   "<= 4 ms", 4.0, readme="one drag step, 1M-vertex object")
gb("interaction", "^BM_DragFirstStep/points:1M/", "the first step of a drag (starts the gesture)")
gb("interaction", "^BM_Hover/points:1M/", "hover test over the same scene", "<= 0.05 ms", 0.05)
gb("interaction", "^BM_UndoDrag/points:10M/", "undo of a drag, 10M points", "<= 50 ms", 50.0, readme="undo of a drag, 10M points")
G = "^BM_GuardedDragStep/guard:"
gb("guarded", G + "off/reads:none/", "a glyph drag step without a shape guard, 1M-vertex sphere (model, evaluation; no view)")
gb("guarded", G + "keep-volume/reads:none/", "the same with Keep Volume (the lattice corrected each step)", "<= 10 ms", 10.0)
gb("guarded", G + "keep-volume/reads:view/", "the same with the view's points and normals")
gb("guarded", G + "keep-centre/reads:none/", "the same with Keep Centre")
gb("animation", "^BM_AnimationFrame", "one animation frame, 1M-vertex sphere (the keyed gesture and the incremental update)")
gb("animation", "^BM_PlaybackFrame", "one playback frame: the same and the view's points and normals (no GL draw)")
gb("quaternion", "^BM_QiFit_points_164_segments_6$", "QI fit of a 164-point spiral, 6 segments, one thread", "<= 10 ms", 10.0,
   readme="QI curve fit, 164 points, 6 segments", env_prefix="OMP_WAIT_POLICY=passive OMP_NUM_THREADS=1")
for fmt_name, what, goals in (("ply", "binary PLY, 1M vertices, 2M triangles", (60.0, 50.0)), ("xyz", ".xyz text, 1M points", (100.0, 100.0))):
    gb("meshio", "^BM_ReadMesh/format:%s/vertices:1000000/" % fmt_name, "read a " + what, "<= %g ms" % goals[0], goals[0])
    gb("meshio", "^BM_WriteMesh/format:%s/vertices:1000000/" % fmt_name, "write a %s (durable: fsync, rename)" % what,
       "<= %g ms" % goals[1], goals[1])

# Python
ffd_py = python_rows.get("ffdkit.pygem.FFD(points), C-ordered input")
numpy_py = python_rows.get("plain numpy (PyGeM's algorithm)")
peer = "not built" if not python_rows else (
    "%.3f x numpy (%s)" % (statistics.median(ffd_py) / statistics.median(numpy_py), fmt(statistics.median(numpy_py)))
    if ffd_py and numpy_py else "-")
add("`ffdkit.pygem.FFD(points)`, 1M points, 4x4x4 Bernstein, 58 % inside a rotated box", ffd_py,
    "" if ffd_py else "not built", env["FFDKIT_BENCH_PYTHON"].replace(build + "/", rel_build + "/"), "<= 10 ms", 10.0,
    "PyGeM's algorithm in numpy: " + peer, readme="Python: `ffdkit.pygem.FFD`, 1M points")

# CLI
cli_cmd = env["FFDKIT_BENCH_CLI"].replace(build + "/", rel_build + "/")
cli_row = len(rows) + 1
for key, what, goal in (("total", "end to end: `ffdkit-cli deform` of a 1M-vertex binary PLY (read, embed, deform, write)", 150.0),
                        ("read", "  of which reading the PLY", 60.0), ("embed", "  of which embedding", 5.0),
                        ("deform", "  of which deforming", 7.0), ("write", "  of which writing", 50.0)):
    add(what, cli.get(key), "" if cli.get(key) else "not built",
        cli_cmd if key == "total" else "the `--timings` split of the runs of row %d" % cli_row, "<= %g ms" % goal, goal,
        readme="CLI: deform a 1M-vertex PLY file, end to end" if key == "total" else None)


def verdict(r):
    if r["samples"] is None or r["limit"] is None:
        return ""
    return "met" if statistics.median(r["samples"]) <= r["limit"] else "not met"


lines = []
w = lines.append
w("# Benchmarks")
w("")
w("Generated by `scripts/bench.sh` (do not edit by hand; re-run it: `scripts/bench.sh`, or")
w("`scripts/bench.sh --quick` for fewer repetitions). Wall times; each row gives the median and the")
w("range (fastest-slowest) of its repetitions. Numbers measured while the machine is busy with other")
w("work run slower and spread more than on an idle machine; the script prints the load average it")
w("saw. Goals are the targets the project set for each operation, and the column beside them says")
w("whether this run's median meets them; a peer ratio below 1 means ffdkit is faster.")
w("")
w("| | |")
w("|---|---|")
w("| machine | %s, %s cores, %s memory, %s |" % (env["FFDKIT_BENCH_CPU"], env["FFDKIT_BENCH_CORES"], env["FFDKIT_BENCH_MEMORY"], env["FFDKIT_BENCH_OS"]))
w("| date | %s |" % env["FFDKIT_BENCH_DATE"])
w("| commit | %s |" % env["FFDKIT_BENCH_COMMIT"])
w("| repetitions | %d per row (Python: %d calls) |" % (reps, 2 * reps + 1))
cores = int(env["FFDKIT_BENCH_CORES"])
other_cores = float(env["FFDKIT_BENCH_OTHER_CORES"])
busy = other_cores > 0.5 * cores
w("| conditions | %s (other work used %.2f cores on average beside the benchmarks) |" % (
    "busy: more than half the cores' worth of other work ran beside the benchmarks, so these are slower and spread more than on an idle machine" if busy
    else "quiet: little else ran beside the benchmarks", other_cores))
w("")
w("| # | what | median | range | goal | | peer |")
w("|---|---|---|---|---|---|---|")
for i, r in enumerate(rows, 1):
    if r["samples"]:
        med, rng = fmt(statistics.median(r["samples"])), fmt_range(r["samples"])
    else:
        med, rng = r["note"], ""
    w("| %d | %s | %s | %s | %s | %s | %s |" % (i, r["what"], med, rng, r["goal"], verdict(r), r["peer"]))
w("")
w("## Generated geometry and export")
w("")
w("Every benchmark of `bench_geometry_*` and `bench_exporters`, and every mesh format's read and")
w("write at 1M vertices (wall time; a write is durable: fsync and rename). The names carry the")
w("sizes; what each times is in the topic's guide ([generators.md](generators.md),")
w("[export.md](export.md), [robustness.md](robustness.md)).")
w("")
w("| program | benchmark | median | range |")
w("|---|---|---|---|")
for key, program in (("all_cardinal", "bench_geometry_cardinal"), ("all_curvenet", "bench_geometry_curvenet"),
                     ("all_g3", "bench_geometry_g3"), ("all_polyhedron", "bench_geometry_polyhedron"),
                     ("all_quaternion", "bench_geometry_quaternion"), ("all_exporters", "bench_exporters"),
                     ("meshio", "bench_meshio")):
    runs = gbench_runs(key)
    if runs is None:
        w("| %s | not built | | |" % program)
        continue
    for name, samples in runs.items():
        w("| %s | `%s` | %s | %s |" % (program, name, fmt(statistics.median(samples)), fmt_range(samples)))
w("")
w("Command: `OMP_WAIT_POLICY=passive %s/bench/<topic>/<program> --benchmark_repetitions=%d` (bench_meshio:" % (rel_build, reps))
w("`--benchmark_filter=vertices:1000000`).")
w("")
w("## Commands")
w("")
w("Run from the repository root after `scripts/build.sh`; the CLI row runs in a folder holding the")
w("1000 x 1000 grid `grid.ply` that `scripts/bench.sh` writes (1,000,000 vertices, 1,996,002")
w("triangles, 38 MB).")
w("")
for i, r in enumerate(rows, 1):
    w("%d. %s" % (i, r["command"] if r["command"].startswith("the ") else "`%s`" % r["command"]))
w("")
w("Blender's lattice modifier on the job of row 1: `%s` (%s)." % (
    env["FFDKIT_BENCH_BLENDER"].replace(build, rel_build),
    "Debian's blender package" if blender is not None else "not installed on this machine; `scripts/setup-blender.sh` installs it"))
w("")
with open(out_path, "w") as f:
    f.write("\n".join(lines))
print("bench.sh: wrote %s" % out_path)

if readme_path:
    table = ["%s, %s cores, %s, commit %s%s:" % (
        env["FFDKIT_BENCH_DATE"], env["FFDKIT_BENCH_CORES"], env["FFDKIT_BENCH_CPU"], env["FFDKIT_BENCH_COMMIT"].split()[0],
        "; the machine was busy with other work, so these are slower than on an idle one" if busy else ""), "",
        "| operation | median | goal | peer |", "|---|---|---|---|"]
    for r in rows:
        if r["readme"]:
            med = fmt(statistics.median(r["samples"])) if r["samples"] else r["note"]
            table.append("| %s | %s | %s | %s |" % (r["readme"], med, r["goal"], r["peer"] or ""))
    text = open(readme_path).read()
    begin, end = "<!-- bench:readme:begin -->", "<!-- bench:readme:end -->"
    if begin in text and end in text:
        head, rest = text.split(begin, 1)
        _, tail = rest.split(end, 1)
        text = head + begin + "\n" + "\n".join(table) + "\n" + end + tail
        open(readme_path, "w").write(text)
        print("bench.sh: updated the table in %s" % readme_path)
    else:
        print("bench.sh: %s has no bench:readme markers; left alone" % readme_path)
PY
