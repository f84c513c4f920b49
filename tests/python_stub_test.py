"""The type stubs (python/quiver.pyi, installed beside the module) name
exactly the module's public functions, classes and Scene and Image members, each
function with the module's own parameters in the same order and the same
keyword-only ones (read from the signatures pybind11 writes into the
docstrings), so the stubs cannot drift from the module."""
import ast
import os
import re

import quiver

STUB = os.path.join(os.path.dirname(quiver.__file__), "quiver.pyi")


def stub_tree():
    assert os.path.exists(STUB), "no quiver.pyi beside the module"
    with open(STUB) as f:
        return ast.parse(f.read())


def stub_parameters(function):
    """(name, keyword-only) of each parameter but self."""
    a = function.args
    names = [(p.arg, False) for p in a.posonlyargs + a.args] + [(p.arg, True) for p in a.kwonlyargs]
    return [n for n in names if n[0] != "self"]


def module_parameters(callable_object):
    """The same from pybind11's signature line: 'name(a: T, b: T = x, *, c: T = y) -> R'."""
    line = callable_object.__doc__.split("\n")[0]
    inside = re.match(r"\w+\((.*)\) ->", line).group(1)
    parameters, keyword_only = [], False
    for part in re.split(r", (?![^\[]*\])", inside):
        if part == "*":
            keyword_only = True
            continue
        name = part.split(":")[0].strip()
        if name != "self":
            parameters.append((name, keyword_only))
    return parameters


def test_the_stubs_name_every_public_name_of_the_module():
    tree = stub_tree()
    stubbed = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            stubbed.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            stubbed.add(node.target.id)
    public = {n for n in dir(quiver) if not n.startswith("_")} | {"__version__"}
    assert stubbed - {"Vector"} == public


def test_each_function_has_the_modules_parameters():
    tree = stub_tree()
    functions = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    for name, node in functions.items():
        assert stub_parameters(node) == module_parameters(getattr(quiver, name)), name
    scene = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Scene")
    members = {n.name: n for n in scene.body if isinstance(n, ast.FunctionDef)}
    assert set(members) == {n for n in dir(quiver.Scene) if not n.startswith("_")}
    for name in ("intersect", "occluded", "to_toml"):
        assert stub_parameters(members[name]) == module_parameters(getattr(quiver.Scene, name)), name
    image = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Image")
    members = {n.name: n for n in image.body if isinstance(n, ast.FunctionDef)}
    assert set(members) == {n for n in dir(quiver.Image) if not n.startswith("_")}
    assert stub_parameters(members["save"]) == module_parameters(quiver.Image.save)
