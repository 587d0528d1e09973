"""The kernels' decorator: kernels copy arrays into slices with ``copy_into``, which writes
what the slice assignment would."""

import ast
from pathlib import Path

import numpy as np

import rocketsim
from rocketsim.jit import copy_into, njit

PACKAGE = Path(rocketsim.__file__).resolve().parent


def _array_slice_assignments(tree: ast.AST) -> list[str]:
    """``a[i:j] = b`` (an array into a slice) inside the kernels (``@njit`` functions) of
    ``tree``, as text; a number into a slice (``a[i:j] = 0.0``) is a fill and not listed."""
    found = []
    for function in ast.walk(tree):
        if not isinstance(function, ast.FunctionDef) or \
                not any("njit" in ast.unparse(d) for d in function.decorator_list):
            continue
        for node in ast.walk(function):
            if not isinstance(node, ast.Assign) or isinstance(node.value, (ast.Constant, ast.UnaryOp)):
                continue
            for target in node.targets:
                for item in target.elts if isinstance(target, ast.Tuple) else [target]:
                    if isinstance(item, ast.Subscript) and any(isinstance(n, ast.Slice)
                                                               for n in ast.walk(item.slice)):
                        found.append(f"{function.name}: {ast.unparse(node)}")
    return found


def test_kernels_copy_arrays_into_slices_without_numbas_shape_check():
    # numba compiles an array assigned into a slice with a check of the two shapes whose
    # error message takes 2-3 s to compile on a cold cache, in each process that first
    # needs it (measured in a cold Falcon 9 flight: 2.3-2.7 s); kernels use copy_into
    found = [f"{path.relative_to(PACKAGE)}: {line}" for path in sorted(PACKAGE.rglob("*.py"))
             for line in _array_slice_assignments(ast.parse(path.read_text()))]
    assert found == []
    # the scan sees the form it forbids
    assert _array_slice_assignments(ast.parse("@njit\ndef f(a, b):\n    a[1:3] = b\n    a[:] = 0.0\n")) == \
        ["f: a[1:3] = b"]


def test_copy_into_writes_the_array_from_the_slot():
    @njit(cache=False)
    def into_column(dst, src):
        copy_into(dst[:, 1], 1, src)
        return dst

    out = into_column(np.zeros((4, 2)), np.array((1.0, 2.0, 3.0)))
    np.testing.assert_array_equal(out, [[0.0, 0.0], [0.0, 1.0], [0.0, 2.0], [0.0, 3.0]])
