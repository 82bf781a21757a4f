#!/usr/bin/env python3
"""Checks that a volume mesh written by ffdkit-cli deform differs from its input only in the
point coordinates (tests/cli/gmsh_test.sh).

usage: volume_mesh_compare.py msh|su2 INPUT OUTPUT
msh: every byte before $Nodes and from $EndNodes on is the same, $Nodes has the same length,
     and (ASCII) only lines of 3 or more numbers inside $Nodes (coordinates) differ; (binary)
     at most 24 bytes per node differ.
su2: the same lines, and only lines after NPOIN= (the point lines) differ.
Prints what differs and exits 1 on the first difference elsewhere.
"""
import sys


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def compare_msh(a, b):
    for data, name in ((a, "input"), (b, "output")):
        if b"$Nodes" not in data or b"$EndNodes" not in data:
            fail(name + " has no $Nodes section")
    na, nb = a.index(b"$Nodes"), b.index(b"$Nodes")
    ea, eb = a.index(b"$EndNodes"), b.index(b"$EndNodes")
    if a[:na] != b[:nb]:
        fail("the bytes before $Nodes differ")
    if a[ea:] != b[eb:]:
        fail("the bytes from $EndNodes on differ ($Elements, tags, physical groups)")
    binary = a.split(b"\n", 2)[1].split()[1] == b"1"
    if binary:
        if ea - na != eb - nb:
            fail("$Nodes changed length in a binary file")
        nodes = int.from_bytes(a[na + 7 + 8:na + 7 + 16], "little")
        differing = sum(1 for x, y in zip(a[na:ea], b[nb:eb]) if x != y)
        if differing > 24 * nodes:
            fail("%d bytes of $Nodes differ, more than 24 per node (%d nodes)" % (differing, nodes))
        return differing
    la, lb = a[na:ea].split(b"\n"), b[nb:eb].split(b"\n")
    if len(la) != len(lb):
        fail("$Nodes has %d lines, was %d" % (len(lb), len(la)))
    changed = 0
    for x, y in zip(la, lb):
        if x != y:
            if len(x.split()) < 3 or len(x.split()) != len(y.split()):
                fail("a line of $Nodes that is not coordinates changed: %r -> %r" % (x, y))
            changed += 1
    return changed


def compare_su2(a, b):
    la, lb = a.split(b"\n"), b.split(b"\n")
    if len(la) != len(lb):
        fail("%d lines, was %d" % (len(lb), len(la)))
    ndime, npoin, start = 0, 0, -1
    for i, line in enumerate(la):
        if line.startswith(b"NDIME="):
            ndime = int(line.split(b"=")[1])
        if line.startswith(b"NPOIN="):
            npoin, start = int(line.split(b"=")[1].split()[0]), i + 1
    changed = 0
    for i, (x, y) in enumerate(zip(la, lb)):
        if x != y:
            if not (start <= i < start + npoin):
                fail("line %d is not a point line and changed: %r -> %r" % (i + 1, x, y))
            if x.split()[ndime:] != y.split()[ndime:]:
                fail("line %d: the point's index changed: %r -> %r" % (i + 1, x, y))
            changed += 1
    return changed


def main():
    kind, path_a, path_b = sys.argv[1:4]
    a, b = open(path_a, "rb").read(), open(path_b, "rb").read()
    changed = compare_msh(a, b) if kind == "msh" else compare_su2(a, b)
    if changed == 0:
        fail("no coordinate changed")
    print("ok: %d coordinate lines or bytes changed, every other byte kept" % changed)


main()
