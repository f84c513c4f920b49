"""Every public function, Scene method and Image.save has a NumPy-style docstring
(python/docstrings.h): a Parameters section naming each of its parameters
(a line may name several, "origins, directions : ...") and a Returns
section, so help() documents every argument."""
import re

import quiver


def sections(doc):
    """{section title: its lines} of a NumPy-style docstring."""
    found, current = {}, None
    lines = doc.split("\n")
    for i, line in enumerate(lines):
        if i + 1 < len(lines) and set(lines[i + 1].strip()) == {"-"} and line.strip():
            current = line.strip()
            found[current] = []
        elif current and not set(line.strip()) <= {"-"}:
            found[current].append(line)
    return found


def documented_names(lines):
    names = set()
    for line in lines:
        if line and not line.startswith(" "):
            names.update(n.strip() for n in line.split(":")[0].split(","))
    return names


def parameters(callable_object):
    signature = callable_object.__doc__.split("\n")[0]
    inside = re.match(r"\w+\((.*)\) ->", signature).group(1)
    return [p.split(":")[0].strip() for p in re.split(r", (?![^\[]*\])", inside) if p not in ("*", "")]


def callables():
    for name in dir(quiver):
        obj = getattr(quiver, name)
        if not name.startswith("_") and callable(obj) and type(obj).__name__ == "builtin_function_or_method":
            yield name, obj
    for name in ("intersect", "occluded", "to_toml"):
        yield "Scene." + name, getattr(quiver.Scene, name)
    yield "Image.save", quiver.Image.save


def test_every_function_documents_each_parameter_and_what_it_returns():
    seen = 0
    for name, obj in callables():
        found = sections(obj.__doc__)
        assert "Returns" in found, name
        expected = {p for p in parameters(obj) if p != "self"}
        assert expected <= documented_names(found.get("Parameters", [])), (name, expected)
        seen += 1
    assert seen >= 10  # six functions, three Scene methods and Image.save


def test_the_scene_class_documents_its_attributes():
    found = sections(quiver.Scene.__doc__)
    assert documented_names(found["Attributes"]) == {"name", "primitive_count", "bounds"}


def test_the_image_class_documents_its_attributes():
    found = sections(quiver.Image.__doc__)
    public = {n for n in dir(quiver.Image) if not n.startswith("_")} - {"save"}
    assert documented_names(found["Attributes"]) == public
