"""SVG documents made plain for svgelements, as SVG defines them.

svgelements (MIT) parses what it is given; a few things of the SVG
document model it does not do are done here on the XML first: ``inherit``
takes the parent's value, a ``<use>`` of a ``<symbol>`` becomes a nested
viewport, a ``<use>`` of another file gets a copy of what it references,
and containers drawn only where referenced move into ``<defs>``.

References
----------
W3C, Scalable Vector Graphics (SVG) 1.1 (Second Edition), Recommendation,
2011: sections 5.6 (``use``), 6.2 (``inherit``). https://www.w3.org/TR/SVG11/
"""

from __future__ import annotations

import copy
import io
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

from medialaxis.errors import InputFileError, UnsupportedFeatureError

__all__ = ["prepared_source", "local_name", "href_of"]

#: Containers whose children are painted only where they are referenced.
_REFERENCED_ONLY = ("symbol", "marker", "mask", "linearGradient", "radialGradient", "filter", "font", "glyph")
#: Containers this reader cannot draw: their semantics would change the shape.
_REFUSED_TAGS = {"switch": "<switch> (conditional processing)", "foreignObject": "<foreignObject>"}
_SVG_NS = "{http://www.w3.org/2000/svg}"


def local_name(tag: Any) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


_XLINK = "{http://www.w3.org/1999/xlink}href"


def href_of(element: Any) -> str | None:
    return element.get(_XLINK) or element.get("href")


def _parse_tree(path: Path) -> Any:
    try:
        return ET.parse(path)
    except Exception as exc:  # noqa: BLE001 - ParseError, OSError, LookupError (bad encoding), ValueError...
        raise InputFileError(f"cannot parse SVG {str(path)!r}: {exc}") from exc


def _external_target(path: Path, href: str, cache: dict[Path, Any]) -> Any:
    """The element ``file#id`` of another SVG file, next to ``path``."""
    name, _, ident = href.partition("#")
    other = (path.parent / name).resolve()
    if other not in cache:
        if not other.is_file():
            raise InputFileError(f"SVG {str(path)!r} uses {href!r}, but {str(other)!r} does not exist")
        cache[other] = _parse_tree(other).getroot()
    root = cache[other]
    found = next((e for e in root.iter() if e.get("id") == ident), None) if ident else root
    if found is None:
        raise InputFileError(f"SVG {str(path)!r} uses {href!r}, but {name!r} has no element with id {ident!r}")
    return found


def _symbol_viewport(use: Any, symbol: Any) -> Any:
    """A ``<use>`` of a ``<symbol>`` as SVG 1.1 section 5.6 draws it: a nested ``<svg>`` of the use's size."""
    group = ET.Element(f"{_SVG_NS}g", {k: v for k, v in use.attrib.items() if k not in (_XLINK, "href", "x", "y",
                                                                                        "width", "height", "id")})
    x, y = use.get("x", "0"), use.get("y", "0")
    if x not in ("0", "") or y not in ("0", ""):
        group.set("transform", f"{group.get('transform', '')} translate({x or 0},{y or 0})".strip())
    viewport = ET.SubElement(group, f"{_SVG_NS}svg", {"width": use.get("width", "100%"),
                                                      "height": use.get("height", "100%")})
    for key in ("viewBox", "preserveAspectRatio", "overflow", "style"):
        if symbol.get(key) is not None:
            viewport.set(key, symbol.get(key))
    viewport.extend(copy.deepcopy(list(symbol)))
    return group


def _style_items(element: Any) -> list[tuple[str, str]]:
    items = []
    for item in (element.get("style") or "").split(";"):
        key, sep, value = item.partition(":")
        if sep:
            items.append((key.strip(), value.strip()))
    return items


def _resolve_inherit(element: Any, parent_values: dict[str, str]) -> None:
    """Replace the keyword ``inherit`` by the parent's value (SVG 1.1 section 6.2), in attributes and styles.

    svgelements would take the keyword for a value (a colour named "inherit").
    """
    values = dict(parent_values)
    for key, value in list(element.attrib.items()):
        if value.strip() == "inherit":
            if key in parent_values:
                element.set(key, parent_values[key])
            else:
                del element.attrib[key]
    items = _style_items(element)
    if any(value == "inherit" for _, value in items):
        kept = [(k, parent_values[k] if v == "inherit" else v) for k, v in items if v != "inherit" or k in parent_values]
        element.set("style", "; ".join(f"{k}: {v}" for k, v in kept))
    values.update({k: v for k, v in element.attrib.items() if isinstance(k, str) and not k.startswith("{")})
    values.update(dict(_style_items(element)))
    for key in ("id", "transform", "x", "y", "width", "height", "d", "points", "style", "class"):
        values.pop(key, None)
    for child in element:
        _resolve_inherit(child, values)


def prepared_source(path: Path) -> tuple[io.BytesIO, dict[str, Any]]:
    """The document made plain for svgelements, as SVG defines it.

    - Containers drawn only where referenced (``symbol``, ``marker``, ``mask``,
      gradients) move into ``<defs>``: svgelements would draw the children of
      elements it does not know where they stand.
    - A ``<use>`` of a ``<symbol>`` becomes a nested ``<svg>`` of the use's
      size (SVG 1.1 section 5.6), so the symbol's viewBox and clipping apply.
    - A ``<use>`` of an element of another file gets a copy of that element.
    """
    tree = _parse_tree(path)
    root = tree.getroot()
    if local_name(root.tag) != "svg":
        raise InputFileError(f"{str(path)!r} is not an SVG document (root element <{local_name(root.tag)}>)")
    _resolve_inherit(root, {})
    ids = {e.get("id"): e for e in root.iter() if e.get("id")}
    external: dict[Path, Any] = {}
    copies = []
    for parent in list(root.iter()):
        for index, child in enumerate(list(parent)):
            if local_name(child.tag) != "use" or not href_of(child):
                continue
            href = href_of(child).strip()
            if href.startswith("#"):
                target = ids.get(href[1:])
            elif "(" in href or "#" not in href:
                continue  # not an IRI of an element: svgelements draws nothing for it, as SVG says
            else:
                target = _external_target(path, href, external)
                if local_name(target.tag) != "symbol":
                    ident = f"medialaxis-external-{len(copies)}"
                    copied = copy.deepcopy(target)
                    copied.set("id", ident)
                    copies.append(copied)
                    child.set(_XLINK, f"#{ident}")
                    child.attrib.pop("href", None)
                    continue
            if target is not None and local_name(target.tag) == "symbol":
                parent.remove(child)
                parent.insert(index, _symbol_viewport(child, target))
    moved = list(copies)
    for parent in root.iter():
        if local_name(parent.tag) in _REFERENCED_ONLY and parent is not root:
            continue
        for child in list(parent):
            name = local_name(child.tag)
            if name in _REFUSED_TAGS:
                raise UnsupportedFeatureError(f"SVG {str(path)!r} uses {_REFUSED_TAGS[name]}, which is not read")
            if name in _REFERENCED_ONLY:
                parent.remove(child)
                moved.append(child)
    if moved:
        defs = ET.Element(f"{_SVG_NS}defs")
        defs.extend(moved)
        root.insert(0, defs)  # first: a <use> finds what it references wherever it stands
    out = io.BytesIO()
    tree.write(out, encoding="utf-8", xml_declaration=True)
    out.seek(0)
    return out, {e.get("id"): e for e in root.iter() if e.get("id")}
