"""The package's import graph: no cycle between modules (lazy imports inside functions
count too), so that the layers only point down."""
import ast
import pathlib

import persson_fast as pf

ROOT = pathlib.Path(pf.__file__).parent

#: cycles still open, each named with the reason; a new cycle fails the test, and so does a
#: listed one that is gone (update the list). None: the surfaces <-> topography pair of old
#: is gone (the table model is handed to topography's binning, and Surface.to_csv writes
#: from surface_base)
KNOWN = set()


def _graph():
    graph = {}
    for f in ROOT.rglob("*.py"):
        parts = ["persson_fast", *f.relative_to(ROOT).with_suffix("").parts]
        is_init = parts[-1] == "__init__"
        if is_init:
            parts = parts[:-1]
        base_of = parts if is_init else parts[:-1]
        deps = set()
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level:
                base = base_of[: len(base_of) - (node.level - 1)]
                if node.module:
                    deps.add(".".join(base + node.module.split(".")))
                else:
                    for a in node.names:
                        sub = ROOT.parent.joinpath(*base, a.name)
                        deps.add(".".join(base + [a.name]) if sub.with_suffix(".py").exists()
                                 or sub.is_dir() else ".".join(base))
        graph[".".join(parts)] = deps
    return graph


def _cycles(graph):
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in graph:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(tuple(sorted(comp)))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return set(out)


def test_no_import_cycle():
    assert _cycles(_graph()) == KNOWN


def test_the_checker_sees_a_cycle():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == {("a", "b", "c")}


def test_kernels_import_no_model_module():
    """The compiled kernels (``_kernels``) depend on nothing above them."""
    graph = _graph()
    for mod, deps in graph.items():
        if mod.startswith("persson_fast._kernels"):
            up = [d for d in deps if not d.startswith("persson_fast._kernels")
                  and d != "persson_fast._jit"]
            assert not up, (mod, up)


def test_import_leaves_scipy_special_for_first_use():
    """``import persson_fast`` (and the command line's module) does not import scipy.special
    (about a third of the import time); the first error function called does, and gives
    scipy's values."""
    import subprocess
    import sys

    code = ("import sys, persson_fast.cli.main; assert 'scipy.special' not in sys.modules; "
            "from persson_fast.analytic import special as _special; import numpy as np; x = np.linspace(-3, 3, 7); "
            "v = [_special.erf(x), _special.erfc(x), _special.erfcx(x), _special.exp1(x + 4)]; "
            "import scipy.special as s; assert 'scipy.special' in sys.modules; "
            "ref = [s.erf(x), s.erfc(x), s.erfcx(x), s.exp1(x + 4)]; "
            "assert all(np.array_equal(a, b) for a, b in zip(v, ref)); print('ok')")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0 and proc.stdout.strip() == "ok", proc.stderr
