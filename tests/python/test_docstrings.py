"""Every public function and class of the ffdkit module says what it does, its arguments and its
errors: help(ffdkit.ffd.Deformer) must be useful. A docstring counts when, after the signature
lines pybind11 writes itself, it has at least two lines of its own (a summary and at least one
line of arguments, returns, raises or detail); every overload of an overloaded function needs
them. Properties and enum values are not checked (one line each is enough for them)."""
import inspect
import re
import types

import pytest

import ffdkit
import ffdkit.pygem

MODULES = {"ffdkit": ffdkit, "ffdkit.ffd": ffdkit.ffd, "ffdkit.widgets": ffdkit.widgets, "ffdkit.scenes": ffdkit.scenes,
           "ffdkit.app": ffdkit.app, "ffdkit.pygem": ffdkit.pygem}
if hasattr(ffdkit._ffdkit, "_cad"):  # builds with OpenCASCADE
    import ffdkit.cad

    MODULES["ffdkit.cad"] = ffdkit.cad

# A pybind11 signature line: "name(arg: type, ...) -> type", or "1. name(...)" in an overload list.
SIGNATURE = re.compile(r"^\s*(\d+\.\s+)?[A-Za-z_][\w.]*\(.*\)(\s*->\s*.*)?\s*$")


def own_lines(text):
    """The non-empty lines of a docstring that pybind11 did not write (signatures, headers)."""
    lines = [line for line in (text or "").splitlines() if line.strip()]
    return [line for line in lines if not SIGNATURE.match(line) and line.strip() != "Overloaded function."]


def overloads(doc):
    """The docstring of each overload (one entry for a function that is not overloaded)."""
    if doc and "Overloaded function." in doc:
        parts = re.split(r"(?m)^\s*\d+\.\s+[A-Za-z_][\w.]*\(.*$", doc)
        return parts[1:]
    return [doc]


def is_enum(cls):
    return hasattr(cls, "__members__") and hasattr(cls, "__int__")


def defined_here(obj):
    return (getattr(obj, "__module__", "") or "").startswith("ffdkit")


def public_callables():
    """(qualified name, object) of every public function, class and method of the module."""
    seen, found = set(), []

    def add(name, obj):
        if id(obj) not in seen:
            seen.add(id(obj))
            found.append((name, obj))

    for module_name, module in MODULES.items():
        for name in dir(module):
            if name.startswith("_"):
                continue
            obj = getattr(module, name)
            if isinstance(obj, types.ModuleType) or not callable(obj) or not defined_here(obj):
                continue
            qualified = f"{module_name}.{name}"
            add(qualified, obj)
            if not inspect.isclass(obj) or is_enum(obj):
                continue
            for member, value in vars(obj).items():
                if member.startswith("_") and member != "__init__":
                    continue
                if isinstance(value, property) or not callable(getattr(obj, member)):
                    continue
                add(f"{qualified}.{member}", getattr(obj, member))
    return found


def test_the_walk_finds_the_api():
    names = {name for name, _ in public_callables()}
    # The calls the tutorials and the README use are found, so the check below covers them.
    for expected in ["ffdkit.ffd.Deformer", "ffdkit.ffd.Deformer.update", "ffdkit.ffd.makeBoxLattice",
                     "ffdkit.widgets.WidgetModel.bind", "ffdkit.scenes.readScene", "ffdkit.pygem.FFD",
                     "ffdkit.LatticeError", "ffdkit.app.Document.undo", "ffdkit.ffd.AxisBasis.Kind"]:
        assert expected in names, expected
    assert len(names) > 250


def test_the_check_rejects_a_missing_or_one_line_docstring():
    assert len(own_lines("f(x: int) -> int\n\nDoes f.\n")) == 1
    assert len(own_lines("f(x: int) -> int\n\nDoes f.\n\nArgs:\n    x: a number.\n")) == 3
    assert own_lines(None) == []
    doc = "Overloaded function.\n\n1. f(x: int) -> int\n\nOne.\n\nArgs: x.\n\n2. f(x: str) -> int\n\nTwo.\n"
    assert [len(own_lines(part)) for part in overloads(doc)] == [2, 1]


def test_every_public_callable_has_a_docstring_of_two_lines_or_more():
    missing = []
    for name, obj in public_callables():
        if name.endswith(".__init__") and obj.__doc__ in (None, object.__init__.__doc__):
            continue  # no constructor of its own (a result type made by the library)
        for part in overloads(obj.__doc__):
            if len(own_lines(part)) < 2:
                missing.append(f"{name}: {own_lines(part)[:1] or 'no docstring'}")
                break
    checked = len(public_callables())
    print(f"{checked - len(missing)} of {checked} public callables documented")
    assert not missing, f"{len(missing)} of {checked} public callables lack a docstring of >= 2 lines:\n" + \
        "\n".join(missing)


def test_help_of_the_deformer_says_what_it_does_its_arguments_and_its_errors():
    text = ffdkit.ffd.Deformer.update.__doc__
    assert "Args:" in text and "lattice" in text and "Raises:" in text and "LatticeError" in text
    assert "Raises:" in ffdkit.ffd.embed.__doc__ and "Cancelled" in ffdkit.ffd.embed.__doc__
