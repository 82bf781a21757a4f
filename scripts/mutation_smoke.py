"""Driver of scripts/mutation-smoke.sh (see its header for what it does and how to call it)."""
import argparse
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

MODULES = ("ffd", "widgets", "geometry")

# Lines that only build messages or check preconditions: a mutation there tests the error text,
# not the mathematics.
SKIP_LINE = re.compile(r'"|\bthrow\b|<<|static_assert|\bassert\(|\bfail\(|^\s*(#|//|/?\*)')

# Each operator: (name, regex, replacement function). The regexes need an operand on the left of
# binary operators (a word character, ')' or ']' and a space) so unary minus and templates stay.
SIGN = re.compile(r"(?<=[\w)\]]) ([+-]) (?=[\w(.])")
COMPARE = re.compile(r"(?<=[\w)\]]) (<=|>=|<|>|==|!=) (?=[\w(.-])")
LOGIC = re.compile(r" (&&|\|\|) ")
CONSTANT = re.compile(r"(?<![\w.])(\d+\.\d*|\d*\.\d+|\d+)(?![\w.])")
INDEX = re.compile(r"(?<=[\[(])([012])(?=[\])])")
COORD = re.compile(r"\.([xyz])\(\)")
DROP = re.compile(r"(?<=[\w)\]]) [+-] [A-Za-z_][\w.:]*(?:\([^()]*\)|\[[^\[\]]*\])*(?=[;),])")

REPLAY = re.compile(r"^(\S+?):(\d+):(\d+)\s+(.+?)\s+('.*'|\".*\") -> ('.*'|\".*\")$")

FLIP = {"+": "-", "-": "+", "<=": "<", "<": "<=", ">=": ">", ">": ">=", "==": "!=", "!=": "==",
        "&&": "||", "||": "&&"}


def code_part(line):
    cut = line.find("//")
    return line if cut < 0 else line[:cut]


def sites(path, text):
    """Every possible mutation of the file: (line index, start, end, replacement, operator)."""
    out = []
    for n, line in enumerate(text.split("\n")):
        if SKIP_LINE.search(line):
            continue
        code = code_part(line)
        for m in SIGN.finditer(code):
            out.append((n, m.start(1), m.end(1), FLIP[m.group(1)], "flip sign"))
        for m in COMPARE.finditer(code):
            out.append((n, m.start(1), m.end(1), FLIP[m.group(1)], "flip comparison"))
        for m in LOGIC.finditer(code):
            out.append((n, m.start(1), m.end(1), FLIP[m.group(1)], "flip logic"))
        for m in CONSTANT.finditer(code):
            v = m.group(1)
            new = str(int(v) + 1) if v.isdigit() else repr(float(v) + 1.0)
            out.append((n, m.start(1), m.end(1), new, "constant + 1"))
        for m in INDEX.finditer(code):
            out.append((n, m.start(1), m.end(1), {"0": "1", "1": "0", "2": "1"}[m.group(1)], "swap index"))
        for m in COORD.finditer(code):
            out.append((n, m.start(1), m.end(1), {"x": "y", "y": "z", "z": "x"}[m.group(1)], "swap coordinate"))
        for m in DROP.finditer(code):
            out.append((n, m.start(), m.end(), "", "drop term"))
    return [(path,) + s for s in out]


def source_files(tree):
    files = []
    for module in MODULES:
        base = os.path.join(tree, module, "src")
        for d, _, names in os.walk(base):
            for name in sorted(names):
                if name.endswith((".cpp", ".h")):
                    files.append(os.path.relpath(os.path.join(d, name), tree))
    return sorted(files)


def target_of(rel):
    """(test target, its folder under tests/) of a mutated source file."""
    parts = rel.split(os.sep)
    if parts[0] in ("ffd", "widgets"):
        return parts[0] + "_tests", os.path.join("tests", parts[0])
    if len(parts) == 3:  # geometry/src/gauss_legendre.cpp: the common core
        return "geometry_core_tests", os.path.join("tests", "geometry")
    return "geometry_%s_tests" % parts[2], os.path.join("tests", "geometry", parts[2])


def sync_tree(root, tree):
    """Copies the tracked and new unignored files of root into tree. A changed file gets a fresh
    mtime (so the mutation build recompiles it); unchanged files are not touched (so it does
    not). Files of the mutated modules that root no longer has are removed from the copy."""
    listed = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=root, check=True,
                            capture_output=True).stdout.decode().split("\0")
    keep = set(filter(None, listed))
    for module in MODULES:
        for d, _, names in os.walk(os.path.join(tree, module)):
            for name in names:
                rel = os.path.relpath(os.path.join(d, name), tree)
                if rel not in keep:
                    os.remove(os.path.join(tree, rel))
    for rel in sorted(keep):
        src, dst = os.path.join(root, rel), os.path.join(tree, rel)
        if not os.path.isfile(src):
            continue
        if os.path.isfile(dst):
            with open(src, "rb") as a, open(dst, "rb") as b:
                if a.read() == b.read():
                    continue
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copyfile(src, dst)


def build(build_dir, target, jobs, log):
    r = subprocess.run(["cmake", "--build", build_dir, "--parallel", str(jobs), "--target", target],
                       stdout=log, stderr=subprocess.STDOUT)
    return r.returncode == 0


def run_tests(build_dir, tree, target, folder, timeout):
    """'passed', 'failed', 'crashed' or 'timed out'."""
    binary = os.path.join(build_dir, folder, target)
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    try:
        r = subprocess.run([binary, "--gtest_fail_fast", "--gtest_brief=1"], cwd=os.path.join(tree, folder),
                           env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timed out"
    if r.returncode == 0:
        return "passed"
    return "failed" if r.returncode == 1 else "crashed"


class Terminated(Exception):
    pass


def main():
    ap = argparse.ArgumentParser(prog="mutation-smoke.sh")
    ap.add_argument("--root", required=True)
    ap.add_argument("--count", type=int, default=None, help="mutants to apply (default 60; --replay: all listed)")
    ap.add_argument("--seed", type=int, default=18)
    ap.add_argument("--timeout", type=float, default=0.0, help="per test run; default 4 x baseline, >= 60 s")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--work", default="")
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--only", default="", help="regex on the file path")
    ap.add_argument("--replay", default="", help="file of --list lines: apply exactly those mutants")
    a = ap.parse_args()
    if a.count is None:
        a.count = 0 if a.replay else 60
    if a.count < 0 or (a.count == 0 and not a.replay):
        print("mutation-smoke: --count must be >= 1, got %d" % a.count, file=sys.stderr)
        return 2
    work = os.path.abspath(a.work or os.path.join(a.root, "build-mutation"))
    tree, build_dir = os.path.join(work, "tree"), os.path.join(work, "tree", "build")
    os.makedirs(tree, exist_ok=True)
    sync_tree(a.root, tree)

    # Draw: every site of every file, shuffled by the seed, then taken round-robin over the three
    # modules so each gets about a third of the mutants whatever their sizes.
    rng = random.Random(a.seed)
    per_module = {m: [] for m in MODULES}
    for rel in source_files(tree):
        if a.only and not re.search(a.only, rel):
            continue
        with open(os.path.join(tree, rel)) as f:
            per_module[rel.split(os.sep)[0]] += sites(rel, f.read())
    for m in MODULES:
        rng.shuffle(per_module[m])
    queue = []
    while any(per_module.values()):
        for m in MODULES:
            if per_module[m]:
                queue.append(per_module[m].pop())
    if a.replay:
        # Lines as --list prints them: "path:line:column  operator  'before' -> 'after'".
        queue = []
        for entry in open(a.replay):
            m = REPLAY.match(entry.strip())
            if not m:
                continue
            rel, n, col, op, before, after = m.group(1), int(m.group(2)) - 1, int(m.group(3)), m.group(4), eval(m.group(5)), eval(m.group(6))
            text = open(os.path.join(tree, rel)).read().split("\n")
            if n >= len(text) or text[n][col:col + len(before)] != before:
                print("mutation-smoke: stale replay entry (the source changed): %s" % entry.strip(), file=sys.stderr)
                continue
            queue.append((rel, n, col, col + len(before), after, op))
        a.count = min(a.count, len(queue)) if a.count else len(queue)
    if a.list:
        for rel, n, s, e, new, op in queue[:a.count]:
            before = open(os.path.join(tree, rel)).read().split("\n")[n][s:e]
            print("%s:%d:%d  %s  %r -> %r" % (rel, n + 1, s, op, before, new))
        return 0

    log = open(os.path.join(work, "build.log"), "w")
    if not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")):
        gen = ["-G", "Ninja"] if shutil.which("ninja") else []
        subprocess.run(["cmake", "-S", tree, "-B", build_dir, *gen, "-DCMAKE_BUILD_TYPE=Release", "-DFFDKIT_BUILD_APP=OFF"],
                       check=True, stdout=log, stderr=subprocess.STDOUT)
    targets = sorted({target_of(q[0]) for q in queue})
    baseline = {}
    for target, folder in targets:
        if not build(build_dir, target, a.jobs, log):
            print("mutation-smoke: baseline build of %s failed (see %s)" % (target, log.name), file=sys.stderr)
            return 2
        t0 = time.monotonic()
        result = run_tests(build_dir, tree, target, folder, timeout=3600)
        baseline[target] = time.monotonic() - t0
        if result != "passed":
            print("mutation-smoke: baseline %s %s unmutated; fix the tests first" % (target, result), file=sys.stderr)
            return 2
        print("baseline %-28s passed in %5.1f s" % (target, baseline[target]), flush=True)

    def on_signal(signum, frame):
        raise Terminated()

    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGHUP, on_signal)
    caught, survivors, applied, skipped = 0, [], 0, 0
    original = None
    try:
        for rel, n, s, e, new, op in queue:
            if applied == a.count:
                break
            path = os.path.join(tree, rel)
            with open(path) as f:
                original = (path, f.read())
            lines = original[1].split("\n")
            before = lines[n]
            lines[n] = before[:s] + new + before[e:]
            with open(path, "w") as f:
                f.write("\n".join(lines))
            target, folder = target_of(rel)
            try:
                if not build(build_dir, target, a.jobs, log):
                    skipped += 1
                    continue
                timeout = a.timeout or max(60.0, 4.0 * baseline[target])
                result = run_tests(build_dir, tree, target, folder, timeout)
            finally:
                with open(path, "w") as f:
                    f.write(original[1])
                original = None
            applied += 1
            ok = result != "passed"
            caught += ok
            print("%2d %-8s %-16s %s:%d  %s" % (applied, "caught" if ok else "SURVIVED", op, rel, n + 1,
                                                 ("(%s)" % result) if ok else ""), flush=True)
            if not ok:
                survivors.append((rel, n + 1, s, op, before[s:e], new, before.strip(), lines[n].strip()))
    except (KeyboardInterrupt, Terminated):
        print("\nmutation-smoke: interrupted; sources restored", file=sys.stderr)
        return 130
    finally:
        if original is not None:
            with open(original[0], "w") as f:
                f.write(original[1])
    print("\nsurvivors:")
    for rel, line, col, op, old, new, before, after in survivors:
        print("  %s:%d:%d  %s  %r -> %r\n    - %s\n    + %s" % (rel, line, col, op, old, new, before, after))
    print("\n%d mutants did not compile and were replaced" % skipped)
    pct = 100.0 * caught / applied if applied else 0.0
    print("caught %d of %d (%.1f %%)" % (caught, applied, pct))
    return 0


if __name__ == "__main__":
    sys.exit(main())
