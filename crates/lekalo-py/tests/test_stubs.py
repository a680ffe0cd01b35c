"""The type stubs (`_lekalo.pyi`) against the native module they describe: every public name of
the module has a stub entry and every stub entry names something real, class by class (members
declared on a stub base class count for its subclasses), and each function's and method's
parameters (names, order, keyword-only or not, defaults) are those of the runtime signature."""

import ast
import inspect
from pathlib import Path

import pytest

import lekalo
import lekalo._lekalo as native

STUB = Path(native.__file__).with_name("_lekalo.pyi")


def parse_stub():
    """Top-level functions and constants, and classes, of the stub file."""
    tree = ast.parse(STUB.read_text())
    names, classes = {}, {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            names[node.name] = node
        elif isinstance(node, ast.ClassDef):
            classes[node.name] = node
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names[node.target.id] = None
    return names, classes


NAMES, CLASSES = parse_stub()


def stub_members(name):
    """Member name -> FunctionDef for a stub class, its stub bases' members included (the
    class's own declaration wins)."""
    node = CLASSES[name]
    out = {}
    for base in node.bases:
        if isinstance(base, ast.Name) and base.id in CLASSES:
            out.update(stub_members(base.id))
    out.update({n.name: n for n in node.body if isinstance(n, ast.FunctionDef)})
    return out


def is_static(fn):
    return any(isinstance(d, ast.Name) and d.id == "staticmethod" for d in fn.decorator_list)


def is_property(fn):
    return any(isinstance(d, ast.Name) and d.id == "property" for d in fn.decorator_list)


def default_of(node):
    """A stub default as a value; Ellipsis (`= ...`) when the stub does not spell it."""
    try:
        return ast.literal_eval(node)
    except ValueError:
        return Ellipsis


def stub_params(fn, method):
    """(name, keyword-only, default) of a stub function, without `self`."""
    a = fn.args
    positional = a.posonlyargs + a.args
    if method and not is_static(fn):
        positional = positional[1:]
    defaults = [inspect.Parameter.empty] * (len(positional) - len(a.defaults)) + [default_of(d) for d in a.defaults]
    out = [(p.arg, False, d) for p, d in zip(positional, defaults)]
    if a.vararg is not None:  # `*axes`: positional, no default
        out.append((a.vararg.arg, False, inspect.Parameter.empty))
    kw = [inspect.Parameter.empty if d is None else default_of(d) for d in a.kw_defaults]
    return out + [(p.arg, True, d) for p, d in zip(a.kwonlyargs, kw)]


def runtime_params(obj):
    """(name, keyword-only, default) of a native function or method, without `self`."""
    sig = inspect.signature(obj)
    return [(p.name, p.kind == p.KEYWORD_ONLY, p.default) for p in sig.parameters.values() if p.name != "self"]


def same_params(stub, runtime):
    if [(n, k) for n, k, _ in stub] != [(n, k) for n, k, _ in runtime]:
        return False
    for (_, _, s), (_, _, r) in zip(stub, runtime):
        if (s is inspect.Parameter.empty) != (r is inspect.Parameter.empty):
            return False
        # a default the stub writes `...`, or one the runtime signature cannot spell, is not compared
        if s is not Ellipsis and r is not Ellipsis and s is not inspect.Parameter.empty and s != r:
            return False
    return True


def public_native_names():
    # `__version__` is public too (the package's version, from the crate's)
    return sorted(n for n in dir(native) if not n.startswith("_") or n == "__version__")


def test_every_native_name_has_a_stub_and_back():
    runtime = set(public_native_names())
    stubbed = {n for n in NAMES} | {n for n in CLASSES if not n.startswith("_")}
    stubbed -= {"ArrayLike", "Array", "Param", "TauChoice", "AnyCurve"}
    assert runtime - stubbed == set(), "native names without a stub entry"
    assert stubbed - runtime == set(), "stub entries that the native module does not have"
    # and everything the package exports from the native module is one of them
    assert {n for n in lekalo.__all__ if hasattr(native, n)} <= stubbed


CLASS_NAMES = [n for n in public_native_names() if isinstance(getattr(native, n), type) and n != "Error"]


@pytest.mark.parametrize("name", CLASS_NAMES)
def test_class_members_match(name):
    cls = getattr(native, name)
    runtime = {n for n in vars(cls) if not n.startswith("_")}
    if "__call__" in vars(cls):
        runtime.add("__call__")
    stub = stub_members(name)
    declared = {n for n in stub if not n.startswith("_") or n == "__call__"}
    assert runtime - declared == set(), f"{name}: members without a stub"
    assert declared - runtime == set(), f"{name}: stub members the class does not have"
    for member, fn in stub.items():
        # properties have no signature, and a slot such as `__call__` shows none at runtime
        if is_property(fn) or member.startswith("__"):
            continue
        got = runtime_params(getattr(cls, member))
        assert same_params(stub_params(fn, method=True), got), f"{name}.{member}: stub {ast.unparse(fn.args)} vs runtime {got}"
    if "__init__" in stub:
        got = runtime_params(cls)
        assert same_params(stub_params(stub["__init__"], method=True), got), f"{name}(): stub vs runtime {got}"


@pytest.mark.parametrize("name", [n for n in public_native_names() if callable(getattr(native, n)) and n not in CLASS_NAMES and n != "Error"])
def test_function_signatures_match(name):
    got = runtime_params(getattr(native, name))
    assert same_params(stub_params(NAMES[name], method=False), got), f"{name}: stub {ast.unparse(NAMES[name].args)} vs runtime {got}"


def test_runtime_signatures_spell_their_defaults():
    # help() and inspect show `times=1`, `degree=3`, not `times=...`: a count argument read
    # through the binding's checked conversion keeps its default visible
    hidden = []
    for name in dir(native):
        obj = getattr(native, name)
        members = vars(obj).items() if inspect.isclass(obj) else [("", obj)]
        for member, f in members:
            text = getattr(f, "__text_signature__", None) or ""
            # PpSpace.contains: its rtol default is a library constant the signature does not
            # spell yet (pp.rs, edited elsewhere)
            if "=..." in text and f"{name}.{member}" != "PpSpace.contains":
                hidden.append(f"{name}.{member}{text}")
    assert not hidden, hidden
    assert inspect.signature(lekalo.interpolate).parameters["degree"].default == 3
    assert inspect.signature(lekalo.BSplineCurve.insert_knot).parameters["times"].default == 1
    assert inspect.signature(lekalo.CurveQuery.length_at).parameters["rtol"].default == 1e-13
