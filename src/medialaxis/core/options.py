"""Method options as frozen dataclasses: each option's name, default, documentation and flag in one place.

Every method of :func:`medialaxis.medial_axis` takes its options as one frozen
dataclass (:class:`Options`), as keywords, or both (keywords win)::

    voronoi_medial_axis(mesh, lam=0.1)
    voronoi_medial_axis(mesh, VoronoiOptions(lam=0.1), samples=40_000)

The method's signature, the ``Parameters`` of its docstring, the command-line
flags of ``medialaxis compute`` and ``docs/options.md`` are all generated from
the dataclass (:func:`takes_options`, :func:`parameter_docs`, :func:`flags`),
so they cannot drift apart.

>>> from dataclasses import dataclass
>>> @dataclass(frozen=True)
... class Demo(Options):
...     size: float = option(1.0, "Edge length.", flag=Flag(help="edge length"))
>>> Demo(size=2.0).size
2.0
>>> Demo(colour="red")
Traceback (most recent call last):
...
TypeError: Demo.__init__() got an unexpected keyword argument 'colour'
"""

from __future__ import annotations

import dataclasses
import inspect
import typing
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any

from medialaxis.errors import InvalidInputError

__all__ = ["Options", "Flag", "option", "make_options", "takes_options", "parameter_docs", "flags", "type_text",
           "argument_kwargs", "flag_value"]

_NO_CONST = object()


@dataclass(frozen=True)
class Flag:
    """How an option appears on the ``medialaxis compute`` command line.

    ``name`` defaults to ``--`` and the option's name with dashes. ``const``
    makes a flag that takes no value (``--repair`` gives ``repair=True``).
    ``counts``: how many values ``nargs="+"`` accepts; one value is passed
    as a number, several as a tuple. ``type`` and ``choices`` default to the
    option's annotation (``float``, ``int``, ``Literal[...]``).
    """

    help: str
    name: str | None = None
    type: Callable[[str], Any] | None = None
    nargs: int | str | None = None
    metavar: str | tuple[str, ...] | None = None
    const: Any = _NO_CONST
    counts: tuple[int, ...] | None = None

    @property
    def takes_value(self) -> bool:
        return self.const is _NO_CONST


def option(default: Any, doc: str, *, flag: Flag | None = None, kind: str | None = None) -> Any:
    """A dataclass field with its documentation (``doc``, numpydoc text) and its command-line ``flag``.

    ``kind`` is the numpydoc type text (default: from the annotation). An
    option without a flag is set from Python only (or ``--option KEY=VALUE``).
    """
    return dataclasses.field(default=default, metadata={"doc": doc, "flag": flag, "kind": kind})


@dataclass(frozen=True)
class Options:
    """Base of the per-method option dataclasses. Values are checked by the method that reads them."""

    def __post_init__(self) -> None:
        for name, choices in _choices(type(self)).items():
            value = getattr(self, name)
            if value not in choices:
                raise InvalidInputError(f"{name} must be one of {', '.join(map(repr, choices))}, got {value!r}")

    def changed(self) -> dict[str, Any]:
        """The options that differ from their defaults, by name."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)
                if getattr(self, f.name) is not f.default and not _same(getattr(self, f.name), f.default)}


def _same(a: Any, b: Any) -> bool:
    try:
        return bool(a == b)
    except (ValueError, TypeError):  # arrays compare element-wise
        return False


_HINTS: dict[type, dict[str, Any]] = {}


def _hints(cls: type) -> dict[str, Any]:
    """The evaluated annotations of ``cls`` (cached: options are made on every call of a method)."""
    if cls not in _HINTS:
        _HINTS[cls] = typing.get_type_hints(cls)
    return _HINTS[cls]


def _choices(cls: type) -> dict[str, tuple[Any, ...]]:
    """The options annotated ``Literal[...]``: the values they accept."""
    return {name: typing.get_args(hint) for name, hint in _hints(cls).items() if typing.get_origin(hint) is typing.Literal}


def _plain(hint: Any) -> Any:
    """``X`` of ``X | None``; the hint itself otherwise."""
    args = [a for a in typing.get_args(hint) if a is not type(None)]
    return args[0] if len(args) == 1 and len(typing.get_args(hint)) == 2 else hint


def type_text(cls: type, field: dataclasses.Field[Any]) -> str:
    """The numpydoc type of an option: ``float, optional``, ``{"a", "b"}``, ``bool``..."""
    if field.metadata.get("kind"):
        return str(field.metadata["kind"])
    hint = _hints(cls)[field.name]
    if typing.get_origin(hint) is typing.Literal:
        return "{" + ", ".join(repr(c).replace("'", '"') for c in typing.get_args(hint)) + "}"
    plain = _plain(hint)
    name = getattr(plain, "__name__", str(plain))
    return f"{name}, optional" if field.default is None else name


def parameter_docs(cls: type) -> str:
    """The numpydoc ``Parameters`` entries of ``cls``'s options, indented four spaces."""
    lines = []
    for field in dataclasses.fields(cls):
        lines.append(f"    {field.name} : {type_text(cls, field)}")
        lines.extend(f"        {line}".rstrip() for line in inspect.cleandoc(field.metadata["doc"]).splitlines())
    return "\n".join(lines)


def make_options(cls: type[Options], options: Any, overrides: Mapping[str, Any], where: str) -> Any:
    """``options`` (options of ``cls`` or of another method, a mapping or None) with ``overrides`` applied, checked.

    Another method's options give what they set (``VoxelOptions(lam=2)`` to the mid-surface), and are
    refused where they set an option this one lacks.
    """
    if type(options) is cls:
        base = {f.name: getattr(options, f.name) for f in dataclasses.fields(cls)}
    elif isinstance(options, Options):
        base = options.changed()
    elif isinstance(options, Mapping):
        base = dict(options)
    elif options is None:
        base = {}
    else:
        raise InvalidInputError(f"{where}: options must be a {cls.__name__} or a mapping, got {type(options).__name__}")
    base.update(overrides)
    names = [f.name for f in dataclasses.fields(cls)]
    unknown = [k for k in base if k not in names]
    if unknown:
        raise InvalidInputError(f"unknown option(s) {', '.join(map(repr, unknown))}; {where} accepts {', '.join(names)}")
    return cls(**base)


def takes_options(cls: type[Options]) -> Callable[[Callable[..., Any]], Any]:
    """Give ``fn(shape, options=None, *, <keywords>, **kwargs)`` the signature and docs of ``cls``'s options.

    The signature shown (``inspect.signature``, ``help``) lists every option
    as a keyword after ``fn``'s own keywords (the progress callback); the
    line ``{options}`` of ``fn``'s docstring becomes the options' numpydoc
    entries. ``fn`` reads its options with :func:`make_options`; its
    ``options_type`` is ``cls``.
    """

    def decorate(fn: Callable[..., Any]) -> Any:
        sig = inspect.signature(fn)
        params = [p for p in sig.parameters.values() if p.kind is not inspect.Parameter.VAR_KEYWORD]
        params += [inspect.Parameter(f.name, inspect.Parameter.KEYWORD_ONLY, default=f.default, annotation=f.type)
                   for f in dataclasses.fields(cls)]
        fn.__signature__ = sig.replace(parameters=params)  # type: ignore[attr-defined]
        whole = (f"    options : {cls.__name__}, optional\n        All the options at once "
                 f"(:class:`{cls.__module__}.{cls.__name__}`); keywords override its fields.")
        fn.__doc__ = (fn.__doc__ or "").replace("    {options}", whole + "\n" + parameter_docs(cls))
        fn.options_type = cls  # type: ignore[attr-defined]
        return fn

    return decorate


def flags(classes: Mapping[str, type[Options]]) -> Iterator[tuple[str, Flag, list[str], Any]]:
    """Each command-line flag once: (option name, its flag, the methods that take it, its annotation).

    ``classes`` maps a label (``"mesh voronoi"``) to that method's options.
    An option that several methods take must have the same flag in each
    (name, arity, type); its help is the first method's.
    """
    seen: dict[str, tuple[Flag, list[str], Any]] = {}
    for label, cls in classes.items():
        for field in dataclasses.fields(cls):
            flag = field.metadata.get("flag")
            if flag is None:
                continue
            if field.name in seen:
                first = seen[field.name][0]
                if (first.name, first.nargs, first.const, first.counts) != (flag.name, flag.nargs, flag.const, flag.counts):
                    raise TypeError(f"option {field.name!r} has different flags in {seen[field.name][1][0]} and {label}")
                seen[field.name][1].append(label)
            else:
                seen[field.name] = (flag, [label], _hints(cls)[field.name])
    for name, (flag, labels, hint) in seen.items():
        yield name, flag, labels, hint


def argument_kwargs(name: str, flag: Flag, hint: Any) -> dict[str, Any]:
    """The keywords of ``argparse``'s ``add_argument`` for an option's flag."""
    if not flag.takes_value:
        return {"action": "store_const", "const": flag.const, "default": None, "dest": name}
    plain = _plain(hint)
    kwargs: dict[str, Any] = {"default": None, "dest": name}
    if typing.get_origin(plain) is typing.Literal:
        kwargs["choices"] = typing.get_args(plain)
    elif flag.type is not None or plain in (int, float, str):
        kwargs["type"] = flag.type or plain
    else:
        raise TypeError(f"the flag of option {name!r} needs a type: its annotation {hint!r} does not say one")
    if flag.nargs is not None:
        kwargs["nargs"] = flag.nargs
    if flag.metavar is not None:
        kwargs["metavar"] = flag.metavar
    return kwargs


def flag_value(name: str, flag: Flag, value: Any) -> Any:
    """The option value of a parsed flag: a list of ``nargs`` values as one number or a tuple.

    Raises
    ------
    ValueError
        The number of values is not one of the flag's ``counts``.
    """
    if not isinstance(value, list):
        return value
    if flag.counts is not None and len(value) not in flag.counts:
        allowed = " or ".join(map(str, flag.counts))
        raise ValueError(f"{flag.name or '--' + name.replace('_', '-')} takes {allowed} values, got {len(value)}")
    return value[0] if len(value) == 1 and flag.counts is not None and 1 in flag.counts else tuple(value)


#: Flags that several domains' options share (one help text for all).
LAM_FLAG = Flag("lambda: smallest contact-set diameter kept (output units)")
THRESHOLD_FLAG = Flag("grey level of the foreground (default: images, Otsu's threshold; volumes, ISO-50: half-way "
                      "between the mean grey levels of Otsu's two classes; 0.5 for bool input)")
SPACING_FLAG = Flag("pixel/voxel size per array axis", type=float, nargs="+", counts=(1, 2, 3))
REPAIR_FLAG = Flag("repair small defects (reported in the metadata)", const=True)
SEED_FLAG = Flag("seed of the random choices (reproducible per seed)", name="--seed", type=int, metavar="N")
