#!/usr/bin/env python3
"""Runs the code blocks of Markdown pages, so that the README and the tutorials cannot drift.

    run_doc_snippets.py --source DIR --build DIR --prefix DIR --python EXE PAGE.md|FOLDER ...

Each page runs in a fresh temporary folder, its blocks in page order, so a later block sees
the files an earlier one wrote. The folder holds links to the source tree's top-level entries
(`scenes`, `widgets`, `docs`, ...) and `build` -> the build folder, so the commands run as
written from the repository root. PATH starts with a folder holding `ffdkit-cli` and `python3`
(the build's interpreter); PYTHONPATH is the build's Python package.

Blocks, by the fence's language:
  sh, bash, shell     run with `bash -euo pipefail`
  python              run with the build's python3
  cmake               the page's CMakeLists.txt (cmake_minimum_required added if missing)
  cpp, c++            main.cpp (the block with `int main`) or a fragment (see below); the page's
                      C++ project is configured against the installed package (--prefix), built
                      and its programs run, after the page's other blocks
  text, console, json, output, ...  output or data: not run, counted
A block without a language is an error: say what it is.

An HTML comment on the line before a block marks it:
  <!-- doc-test: skip REASON -->          not run (the reason is printed and counted)
  <!-- doc-test: needs-display -->        run under xvfb-run when $DISPLAY is unset
  <!-- doc-test: file NAME -->            written to NAME in the page's folder, not run itself
  <!-- doc-test: cpp-fragment H1 H2 -->   a C++ block without main(): compiled inside a main()
                                          after `#include "H1"` ..., and run
  <!-- doc-test: expect-output TEXT -->   the block must print TEXT (a substring)

Exit 0 when every block ran and passed; 1 when a block failed (its page, line, output); 2 on
a page this script cannot read (a block without a language, an unknown marker).
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field

RUN_KINDS = {"sh": "shell", "bash": "shell", "shell": "shell", "python": "python", "cmake": "cmake",
             "cpp": "cpp", "c++": "cpp"}
OUTPUT_KINDS = {"text", "console", "output", "json", "ini", "yaml", "diff", "markdown", "md", "plain"}
BLOCK_TIMEOUT_S = 300


class PageError(Exception):
    """A page this script cannot read as written."""


@dataclass
class Block:
    page: str
    line: int  # 1-based line of the opening fence
    language: str
    code: str
    markers: dict = field(default_factory=dict)

    @property
    def where(self):
        return f"{self.page}:{self.line}"


def parse_page(path):
    """The fenced blocks of a Markdown page, with the doc-test markers just before each."""
    blocks, pending = [], {}
    lines = open(path, encoding="utf-8").read().splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        marker = re.match(r"\s*<!--\s*doc-test:\s*(\S+)\s*(.*?)\s*-->\s*$", line)
        if marker:
            name, arg = marker.group(1), marker.group(2)
            if name not in ("skip", "needs-display", "file", "cpp-fragment", "expect-output"):
                raise PageError(f"{path}:{i + 1}: unknown doc-test marker '{name}'")
            if name == "skip" and not arg:
                raise PageError(f"{path}:{i + 1}: 'doc-test: skip' needs a reason")
            pending[name] = arg
            i += 1
            continue
        fence = re.match(r"^(\s*)(```+|~~~+)\s*([^\s`]*)", line)
        if not fence:
            if line.strip():
                pending = {}  # a marker applies to the block right after it
            i += 1
            continue
        indent, ticks, language = fence.group(1), fence.group(2), fence.group(3).lower()
        start = i
        body = []
        i += 1
        while i < len(lines) and not lines[i].strip().startswith(ticks):
            body.append(lines[i][len(indent):] if lines[i].startswith(indent) else lines[i])
            i += 1
        if i == len(lines):
            raise PageError(f"{path}:{start + 1}: code block never closed")
        i += 1
        if not language:
            raise PageError(f"{path}:{start + 1}: code block without a language (use ```text for output)")
        blocks.append(Block(path, start + 1, language, "\n".join(body) + "\n", pending))
        pending = {}
    return blocks


def link_tree(folder, source, build):
    """Links the source tree's top-level folders and the build folder into `folder`. Files are
    not linked: a block that writes CMakeLists.txt or README.md writes its own, never the
    source tree's."""
    for entry in os.listdir(source):
        if entry.startswith(".") or entry == "build" or entry.startswith("build-"):
            continue
        if not os.path.isdir(os.path.join(source, entry)):
            continue
        os.symlink(os.path.join(source, entry), os.path.join(folder, entry))
    os.symlink(build, os.path.join(folder, "build"))


def tools_folder(scratch, build, python):
    """A folder for the front of PATH: ffdkit-cli and python3 of this build."""
    tools = os.path.join(scratch, "tools")
    os.makedirs(tools)
    os.symlink(os.path.join(build, "app", "cli", "ffdkit-cli"), os.path.join(tools, "ffdkit-cli"))
    os.symlink(python, os.path.join(tools, "python3"))
    return tools


def page_env(base, folder):
    """The environment of one page's blocks: the C++ projects they configure compile through
    ccache when it is installed (CMake reads CMAKE_CXX_COMPILER_LAUNCHER from the environment),
    with paths below the page's folder hashed relative to it, so that the next run of the test,
    in another temporary folder, finds the objects in the cache."""
    env = dict(base)
    if shutil.which("ccache") and "CMAKE_CXX_COMPILER_LAUNCHER" not in env:
        env.update({"CMAKE_CXX_COMPILER_LAUNCHER": "ccache", "CCACHE_BASEDIR": folder, "CCACHE_NOHASHDIR": "1"})
    return env


def run(command, cwd, env, block, display):
    if display and not env.get("DISPLAY"):
        if shutil.which("xvfb-run") is None:
            return 1, f"{block.where}: needs a display and xvfb-run is not installed"
        command = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24"] + command
    try:
        done = subprocess.run(command, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True, timeout=BLOCK_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return 1, f"timed out after {BLOCK_TIMEOUT_S} s"
    return done.returncode, done.stdout


def cpp_project(folder, blocks, cmake_block):
    """Writes the page's C++ project; returns the executables to run, in page order."""
    cmake = cmake_block.code if cmake_block else (
        "project(doc_snippets LANGUAGES C CXX)\nfind_package(ffdkit REQUIRED)\n")
    if "cmake_minimum_required" not in cmake:
        cmake = "cmake_minimum_required(VERSION 3.25)\n" + cmake
    programs = []
    for n, block in enumerate(blocks):
        if "cpp-fragment" in block.markers:
            headers = block.markers["cpp-fragment"].split()
            source = f"fragment_{n}.cpp"
            with open(os.path.join(folder, source), "w") as out:
                out.write("".join(f'#include "{h}"\n' for h in headers))
                out.write("#include <numbers>\nusing namespace ffdkit;\nint main() {\n")
                out.write(f"#line 1 \"{block.where}\"\n{block.code}}}\n")
            target = f"doc_fragment_{n}"
            cmake += (f"add_executable({target} {source})\ntarget_link_libraries({target} PRIVATE ffdkit::scenes)\n"
                      f"target_compile_features({target} PRIVATE cxx_std_20)\n")
            programs.append((target, block))
        elif re.search(r"\bint\s+main\s*\(", block.code):
            if cmake_block is None:
                raise PageError(f"{block.where}: a C++ program needs the page's ```cmake block before it")
            target = re.search(r"add_executable\(\s*(\S+)\s+main\.cpp", cmake_block.code)
            if not target:
                raise PageError(f"{cmake_block.where}: the cmake block does not build main.cpp")
            with open(os.path.join(folder, "main.cpp"), "w") as out:
                out.write(f"#line 1 \"{block.where}\"\n{block.code}")
            programs.append((target.group(1), block))
        else:
            raise PageError(f"{block.where}: a C++ block without main() needs '<!-- doc-test: cpp-fragment HEADERS -->'")
    with open(os.path.join(folder, "CMakeLists.txt"), "w") as out:
        out.write(cmake)
    return programs


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", required=True)
    parser.add_argument("--build", required=True)
    parser.add_argument("--prefix", required=True, help="an install of this build (cmake --install)")
    parser.add_argument("--python", required=True)
    parser.add_argument("--keep", action="store_true", help="keep the temporary folders")
    parser.add_argument("--verbose", action="store_true", help="print every block's output")
    parser.add_argument("pages", nargs="+")
    args = parser.parse_args()
    source, build, prefix = (os.path.realpath(p) for p in (args.source, args.build, args.prefix))
    pages = []
    for page in args.pages:  # a folder stands for its *.md pages, in name order
        if os.path.isdir(page):
            pages += sorted(os.path.join(page, name) for name in os.listdir(page) if name.endswith(".md"))
        else:
            pages.append(page)

    counts = {"shell": 0, "python": 0, "cpp": 0, "cmake": 0, "output": 0, "skipped": 0, "needs-display": 0,
              "file": 0}
    file_kinds = {}  # blocks written as files, by kind (later blocks build or run them)
    failures = []
    scratch = tempfile.mkdtemp(prefix="ffdkit-doc-snippets-")
    try:
        tools = tools_folder(scratch, build, os.path.realpath(args.python))
        base_env = env = dict(os.environ)
        env["PATH"] = tools + os.pathsep + env.get("PATH", "")
        env["PYTHONPATH"] = os.path.join(build, "python")
        env["PYTHONDONTWRITEBYTECODE"] = "1"
        env.setdefault("OMP_WAIT_POLICY", "passive")
        # mpirun in the tutorials: tests may run as root (a container) on fewer cores than ranks.
        env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                    "OMPI_MCA_rmaps_base_oversubscribe": "1", "OMPI_MCA_mpi_yield_when_idle": "1"})
        for page in pages:
            try:
                blocks = parse_page(page)
            except PageError as error:
                print(f"error: {error}", file=sys.stderr)
                return 2
            folder = os.path.join(scratch, re.sub(r"[^A-Za-z0-9]+", "-", os.path.relpath(page, source)))
            os.makedirs(folder)
            link_tree(folder, source, build)
            env = page_env(base_env, folder)
            cpp_blocks, cmake_block = [], None
            for block in blocks:
                kind = RUN_KINDS.get(block.language)
                if kind is None:
                    if block.language not in OUTPUT_KINDS:
                        print(f"error: {block.where}: unknown block language '{block.language}'", file=sys.stderr)
                        return 2
                    counts["output"] += 1
                    continue
                if "skip" in block.markers:
                    counts["skipped"] += 1
                    print(f"skip {block.where} ({kind}): {block.markers['skip']}")
                    continue
                if "file" in block.markers:
                    name = block.markers["file"]
                    target = os.path.join(folder, name)
                    if os.path.realpath(os.path.dirname(target)) != os.path.realpath(folder) or os.path.islink(target):
                        print(f"error: {block.where}: 'doc-test: file {name}' must name a new file in the page's folder",
                              file=sys.stderr)
                        return 2
                    with open(target, "w") as out:
                        out.write(block.code)
                    counts["file"] += 1
                    file_kinds[kind] = file_kinds.get(kind, 0) + 1
                    print(f"file {block.where} ({kind}) -> {name}")
                    continue
                if kind == "cmake":
                    if cmake_block is not None:
                        raise SystemExit(f"error: {block.where}: a page has one cmake block")
                    cmake_block = block
                    counts["cmake"] += 1
                    continue
                if kind == "cpp":
                    cpp_blocks.append(block)
                    continue
                if kind == "shell":
                    command = ["bash", "-euo", "pipefail", "-c", block.code]
                else:
                    script = os.path.join(folder, f".doc_block_{block.line}.py")
                    with open(script, "w") as out:
                        out.write(block.code)
                    command = [os.path.realpath(args.python), script]
                display = "needs-display" in block.markers
                code, output = run(command, folder, env, block, display)
                expected = block.markers.get("expect-output")
                if code == 0 and expected and expected not in output:
                    code, output = 1, output + f"\n(expected the output to contain '{expected}')"
                counts[kind] += 1
                counts["needs-display"] += display
                print(f"{'ok  ' if code == 0 else 'FAIL'} {block.where} ({kind})")
                if args.verbose:
                    print(output)
                if code != 0:
                    failures.append((block, output))
            if cpp_blocks:
                project = os.path.join(folder, "doc-cpp-project")
                os.makedirs(project)
                try:
                    programs = cpp_project(project, cpp_blocks, cmake_block)
                except PageError as error:
                    print(f"error: {error}", file=sys.stderr)
                    return 2
                binary = os.path.join(project, "build")
                configure = ["cmake", "-S", project, "-B", binary, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                             f"-DCMAKE_PREFIX_PATH={prefix}"]
                code, output = run(configure, folder, env, cpp_blocks[0], False)
                if code == 0:
                    code, output = run(["cmake", "--build", binary], folder, env, cpp_blocks[0], False)
                if code != 0:
                    for block in cpp_blocks:
                        print(f"FAIL {block.where} (cpp: the page's project did not build)")
                    failures.append((cpp_blocks[0], output))
                    counts["cpp"] += len(cpp_blocks)
                    continue
                for target, block in programs:
                    code, output = run([os.path.join(binary, target)], folder, env, block, False)
                    counts["cpp"] += 1
                    print(f"{'ok  ' if code == 0 else 'FAIL'} {block.where} (cpp, {target})")
                    if args.verbose:
                        print(output)
                    if code != 0:
                        failures.append((block, output))
    finally:
        if args.keep:
            print(f"kept {scratch}")
        else:
            shutil.rmtree(scratch, ignore_errors=True)

    ran = counts["shell"] + counts["python"] + counts["cpp"]
    print(f"ran {ran} blocks: {counts['shell']} shell, {counts['python']} Python, {counts['cpp']} C++ "
          f"(with {counts['cmake']} cmake projects; {counts['needs-display']} under a display); "
          f"{counts['file']} written as files ({', '.join(f'{n} {k}' for k, n in sorted(file_kinds.items())) or 'none'}: "
          f"later blocks build or run them), {counts['skipped']} skipped with a reason, "
          f"{counts['output']} output or data blocks not run; {len(pages)} pages")
    for block, output in failures:
        print(f"\n--- {block.where} ({block.language}) failed:\n{block.code}--- its output:\n{output}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
