"""What rocketsim's site generates from the code at build time.

* :class:`KernelDocumenter`: autodoc documents a compiled kernel (``rocketsim.jit.Kernel``)
  as the Python function it compiles, so the reference shows its signature and docstring.
* :func:`code_reference`: a cross-reference to a name of the library the site does not
  document (an internal module, a kernel's constant) is shown as code instead of a link,
  if that name exists in the code; one to a name that does not (a moved or deleted
  function) still fails the build.
* :func:`plain_help`: the command line's help is plain text (what a terminal shows), so a
  ``*`` in it (``scenarios/*.yaml``) is a star, not reStructuredText's emphasis.
* the file-format pages (``reference/files/<kind>.rst``): every field of the scenario,
  vehicle, site, mission, weather and campaign files, read from the JSON Schema of the
  pydantic models that validate them (their types, defaults, units and bounds), written
  into the source folder when the build starts, so a new field is documented without
  editing a page.
* :class:`Output`: the ``{output}`` block of a page a reader runs, what the code block
  before it prints, shown as plain text under it (tests/docs/test_docs_pages.py runs the code
  and compares what it prints now with the block).
"""

from __future__ import annotations

import re
from pathlib import Path

from docutils import nodes
from sphinx.ext.autodoc import FunctionDocumenter
from sphinx.util.docutils import SphinxDirective

FILES = "reference/files"


class KernelDocumenter(FunctionDocumenter):
    """A numba kernel, documented as the Python function it compiles."""

    objtype = "kernel"
    directivetype = "function"
    priority = FunctionDocumenter.priority + 10

    @classmethod
    def can_document_member(cls, member, membername, isattr, parent) -> bool:
        from rocketsim.jit import Kernel
        return isinstance(member, Kernel)

    def import_object(self, raiseerror: bool = False) -> bool:
        found = super().import_object(raiseerror)
        if found:
            self.object = self.object.py_func
        return found


def _module_of(path: str):
    """The deepest module ``path`` (``package.module.Name.attr``) names and the names after
    it, or None when no prefix of it imports."""
    import importlib
    parts = path.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            return importlib.import_module(".".join(parts[:cut])), parts[cut:]
        except ImportError:
            continue
    return None


def _exists(path: str) -> bool:
    """Whether ``path`` (``package.module.Name.attr``) names something importable, or an
    attribute a class's instances set (``self.name = ...`` in its source)."""
    import inspect
    walked = _module_of(path)
    if walked is None:
        return False
    found, rest = walked
    for i, name in enumerate(rest):
        if hasattr(found, name):
            found = getattr(found, name)
        elif i == len(rest) - 1 and inspect.isclass(found):
            return f"self.{name} =" in inspect.getsource(found) or name in getattr(
                found, "__annotations__", {})
        else:
            return False
    return True


def _home(path: str) -> str | None:
    """The module that defines what ``path`` names (``rocketsim.api.SizeEstimate``, re-exported,
    is defined in ``rocketsim.api.file_size``), or None."""
    walked = _module_of(path)
    if walked is None:
        return None
    found, rest = walked
    for name in rest:
        found = getattr(found, name, None)
        if found is None:
            return None
    return getattr(found, "__module__", None)


_DOCSTRING_OF = re.compile(r"docstring of ([\w.]+)")


def code_reference(app, env, node, contnode):
    """A Python cross-reference nothing on the site documents: shown as code when it names
    something in rocketsim, as written or relative to the module (and class) whose
    docstring holds it, or to the module defining that class or function (documented
    where it is re-exported), else left unresolved, which nitpicky mode reports. A bare
    name in a signature's type hint (no docstring around it) is looked for in the
    modules of the library already imported."""
    import sys
    if node.get("refdomain") != "py" or not node.get("reftarget"):
        return None
    target = node["reftarget"].lstrip("~.")
    contexts = [f"{node.get('py:module') or ''}.{node.get('py:class') or ''}".strip(".")]
    where = _DOCSTRING_OF.search(node.source or "")
    if where:
        contexts.append(where.group(1))
        contexts += [_home(where.group(1)), _home(where.group(1).rsplit(".", 1)[0])]
    candidates = [target]
    for context in filter(None, contexts):
        parts = context.split(".")
        candidates += [".".join(parts[:cut] + [target]) for cut in range(len(parts), 0, -1)]
    if not where and "." not in target:
        candidates += [f"{name}.{target}" for name in sorted(sys.modules)
                       if name.startswith("rocketsim.") and hasattr(sys.modules[name], target)]
    for candidate in candidates:
        if candidate.split(".")[0] in ("rocketsim", "rocketsim_cli") and _exists(candidate):
            return contnode
    return None


_STAR = re.compile(r"(?<!\\)\*")


def plain_help(app, ctx, lines: list[str]) -> None:
    """Escape the stars of a command's help lines (sphinx-click's events pass the lines,
    changed in place)."""
    lines[:] = [_STAR.sub(r"\\*", line) if not line.lstrip().startswith("..") else line
                for line in lines]


# --- file formats, from the JSON Schema ------------------------------------------------

# A page per kind of file: its title, what it is, and the models at its root. A model
# (a JSON Schema definition) is documented on the first page, in this order, whose roots
# reach it; the scenario's page keeps what no other kind reaches.
KINDS = {
    "vehicle": ("Vehicle files", "A vehicle: one rigid body, or a stack of stages with "
                "their tanks, engines, motors, parachutes and aerodynamics. A scenario's "
                "``spacecraft:`` is a vehicle file too."),
    "site": ("Site files", "A launch site: where the pad is, its height and the pads a "
             "mission may name as its target."),
    "mission": ("Mission files", "A mission: its epoch, where it starts (a site, an orbit "
                "or a state), its target, its duration and its gravity."),
    "weather": ("Weather", "The day's air, as a scenario's ``weather:`` (inline or a file), "
                "one of these kinds."),
    "scenario": ("Scenario files", "What ``rocketsim fly`` flies: a vehicle, a site, a "
                 "mission, the weather and the programs, inline or as paths to their own "
                 "files (relative to the scenario file)."),
    "campaign": ("Campaign files", "A Monte Carlo campaign: a scenario flown many times "
                 "with dispersed inputs (``rocketsim campaign run``)."),
}


def _schemas() -> dict[str, dict]:
    """Kind -> (its JSON Schema, the names of the definitions at its root)."""
    from rocketsim import api
    from rocketsim.campaigns.spec import CampaignSpec
    scenario = api.schema("scenario")
    weather = scenario["properties"]["weather"]["anyOf"][0]["oneOf"]
    return {
        "vehicle": (api.schema("vehicle"), None),
        "site": (api.schema("site"), None),
        "mission": (api.schema("mission"), None),
        "weather": (scenario, [ref["$ref"].rsplit("/", 1)[1] for ref in weather]),
        "scenario": (scenario, None),
        "campaign": (CampaignSpec.model_json_schema(), None),
    }


def _refs(node) -> list[str]:
    """The definitions a schema node names directly, in the order it names them."""
    found: list[str] = []
    if isinstance(node, dict):
        if "$ref" in node:
            found.append(node["$ref"].rsplit("/", 1)[1])
        for value in node.values():
            found += _refs(value)
    elif isinstance(node, list):
        for value in node:
            found += _refs(value)
    return found


def _reach(schema: dict, roots: list[str] | None) -> list[str]:
    """Every definition reachable from ``roots`` (None: the schema's own fields), breadth
    first: a model's section comes after the sections of the models that name it."""
    defs = schema.get("$defs", {})
    todo = list(roots) if roots is not None else _refs(schema.get("properties", {}))
    seen: list[str] = []
    while todo:
        name = todo.pop(0)
        if name in seen or name not in defs:
            continue
        seen.append(name)
        todo += _refs(defs[name])
    return seen


_ROLE = re.compile(r":[a-z:]+:`~?([^`<]*?)(?:\s*<([^>]*)>)?`")


def _text(description: str) -> str:
    """A docstring or field description as plain reStructuredText: cross-reference roles
    (to modules the file reference does not document) become literal names."""
    return _ROLE.sub(lambda m: f"``{(m.group(1) or m.group(2)).strip()}``", description).strip()


def _label(name: str) -> str:
    return f"file-{name.lower()}"


def _type(node: dict) -> str:
    """A schema node's type in words, definitions linked to their sections."""
    if "$ref" in node:
        name = node["$ref"].rsplit("/", 1)[1]
        return f":ref:`{name} <{_label(name)}>`"
    for key in ("anyOf", "oneOf"):
        if key in node:
            kinds = [_type(n) for n in node[key]]
            if {"number", "string"} <= set(kinds) and len(kinds) == 2 and node[key][0].get("type") == "number":
                return "quantity (a number in SI, or a string with a unit)"
            return " or ".join(dict.fromkeys(kinds))
    if "const" in node:
        return f"``{node['const']!r}``" if not isinstance(node["const"], str) else f"``{node['const']}``"
    if "enum" in node:
        return "one of " + ", ".join(f"``{v}``" for v in node["enum"])
    kind = node.get("type")
    if kind == "string" and "pattern" in node and "ya?ml" in node["pattern"]:
        return "path to a YAML file"
    if kind == "string" and node.get("format") == "path":
        return "path"
    if kind == "string" and node.get("format") in ("date-time", "date"):
        return "UTC date and time (ISO 8601)"
    if kind == "array":
        if "prefixItems" in node:
            return "[" + ", ".join(_type(n) for n in node["prefixItems"]) + "]"
        return "list of " + (_type(node["items"]) if "items" in node else "values")
    if kind == "object":
        extra = node.get("additionalProperties")
        return "mapping of names to " + _type(extra) if isinstance(extra, dict) else "mapping"
    if kind == "null":
        return "null"
    if kind == "integer":
        return "integer"
    if kind == "number":
        return "number"
    if kind == "boolean":
        return "true or false"
    if kind == "string":
        return "string"
    return "any value"


def _default(value) -> str:
    if value is None:
        return "none"
    if isinstance(value, bool):
        return "true" if value else "false"
    return f"``{value}``" if value != "" else "empty"


def _fields(model: dict) -> list[str]:
    """A list of a model's fields: name, type, required or its default, description."""
    lines: list[str] = []
    required = set(model.get("required", ()))
    for name, node in model.get("properties", {}).items():
        node_type = dict(node)
        node_type.pop("description", None)
        if "anyOf" in node and node.get("anyOf", [{}])[-1] == {"type": "null"} and len(node["anyOf"]) > 1:
            node_type["anyOf"] = node["anyOf"][:-1]
        when = "required" if name in required else (f"default {_default(node['default'])}"
                                                    if "default" in node else "optional")
        text = _text(node.get("description", ""))
        item = f"``{name}`` ({_type(node_type)}; {when})" + (f": {text}" if text else "")
        lines += ["- " + line if i == 0 else "  " + line if line else ""
                  for i, line in enumerate(item.splitlines())]
    lines.append("")
    return lines


def _section(title: str, char: str) -> list[str]:
    return [title, char * len(title), ""]


def file_page(kind: str, schema: dict, owned: list[str]) -> str:
    """The reStructuredText page of one kind of file: its own fields, then a section per
    model of its own that they reach."""
    title, about = KINDS[kind]
    lines = [f".. _file-kind-{kind}:", ""]
    if kind not in ("weather", "scenario"):
        lines += [f".. _{_label(schema['title'])}:", ""]
    lines += [*_section(title, "="), about, ""]
    if kind != "weather":
        if schema.get("description"):
            lines += [_text(schema["description"]), ""]
        lines += ["Its fields:", "", *_fields(schema)]
    defs = schema.get("$defs", {})
    for name in owned:
        model = defs[name]
        lines += [f".. _{_label(name)}:", "", *_section(name, "-")]
        if model.get("description"):
            lines += [_text(model["description"]), ""]
        if "properties" in model:
            lines += _fields(model)
        else:
            lines += [f"A value: {_type(model)}.", ""]
    return "\n".join(lines) + "\n"


def file_pages() -> dict[str, str]:
    """Page name -> text of every file-format page."""
    schemas = _schemas()
    owner: dict[str, str] = {}
    for kind, (schema, roots) in schemas.items():
        if kind == "campaign":
            continue
        reached = _reach(schema, roots)
        if kind in ("vehicle", "site", "mission"):
            reached.insert(0, schema["title"])
        for name in reached:
            owner.setdefault(name, kind)
    pages = {}
    for kind, (schema, roots) in schemas.items():
        reached = _reach(schema, roots)
        owned = [n for n in reached if kind == "campaign" or owner.get(n) == kind]
        if kind in ("vehicle", "site", "mission"):
            # the root model's own fields are the page's top; the models it reaches follow
            owned = [n for n in owned if n != schema["title"]]
        pages[kind] = file_page(kind, schema, owned)
    return pages


def write_generated_pages(app) -> None:
    """Write the generated pages into the source folder (unchanged files are left alone,
    so an incremental build rereads only what changed)."""
    folder = Path(app.srcdir) / FILES
    folder.mkdir(parents=True, exist_ok=True)
    wanted = {f"{kind}.rst": text for kind, text in file_pages().items()}
    for path in folder.glob("*.rst"):
        if path.name not in wanted:
            path.unlink()
    for name, text in wanted.items():
        path = folder / name
        if not path.exists() or path.read_text() != text:
            path.write_text(text)


class Output(SphinxDirective):
    """What the code block before it prints: a literal block of plain text (no highlighting),
    styled apart from the code (``output`` class, docs/_static/output.css)."""

    has_content = True

    def run(self):
        text = "\n".join(self.content)
        block = nodes.literal_block(text, text, classes=["output"])
        block["language"] = "none"
        self.set_source_info(block)
        return [block]


def setup(app):
    app.add_autodocumenter(KernelDocumenter)
    app.add_directive("output", Output)
    app.connect("builder-inited", write_generated_pages)
    app.connect("missing-reference", code_reference)
    for part in ("description", "options", "arguments", "epilog"):
        app.connect(f"sphinx-click-process-{part}", plain_help)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
