"""``medialaxis compute``: one input to its outputs, or many inputs to a folder (:mod:`medialaxis.cli.batch`)."""

from __future__ import annotations

import argparse
import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from medialaxis._dispatch import DEFAULT_METHOD, METHODS
from medialaxis._help import HelpFormatter, UsageError
from medialaxis._help import print_error as _fail
from medialaxis.core.formats import limits_text, needs_text
from medialaxis.core.io import WRITERS
from medialaxis.core.options import Flag, argument_kwargs, flag_value, flags
from medialaxis.errors import MedialAxisError

__all__ = ["add_compute", "compute_options", "check_kinds", "check_outputs"]


def _parse_option(text: str) -> tuple[str, Any]:
    key, sep, value = text.partition("=")
    if not sep or not key:
        raise UsageError(f"--option expects KEY=VALUE, got {text!r}")
    try:
        return key.replace("-", "_"), json.loads(value)
    except json.JSONDecodeError:
        return key.replace("-", "_"), value


def check_outputs(
    inputs: Sequence[Path], outputs: Sequence[Path], formats: Sequence[str] | None = None, option: str = "--output"
) -> None:
    """Refuse, before any work, outputs that are an input file, of an unknown format, or not writable."""
    from medialaxis.core.formats import suffix_of, writer_missing
    from medialaxis.core.io import WRITERS, check_writable

    formats = tuple(WRITERS) if formats is None else tuple(formats)
    existing = [p for p in inputs if p.exists()]
    for out in outputs:
        if out.exists() and any(out.samefile(p) for p in existing):
            raise UsageError(f"refusing to overwrite the input file {str(out)!r}")
        suffix = suffix_of(out)
        if suffix not in formats:
            raise UsageError(
                f"{option}: unsupported output format {suffix or '(none)'!r} for {str(out)!r}; use one of {', '.join(formats)}"
            )
        missing = writer_missing(suffix)
        if missing is not None:
            raise UsageError(f"{option} {str(out)!r}: {missing}")
        check_writable(out)


def check_kinds(outputs: Sequence[Path], domain: str, method: str | None, source: Path | None = None) -> None:
    """Refuse, before any work, outputs that cannot hold what ``method`` gives for ``domain`` inputs.

    A saved result (its kind is known once read) and a method unknown here are let through: saving
    checks again before writing anything. ``source``: the input, named in the message of a batch
    (its outputs come from ``--format``).
    """
    from medialaxis.core.io import kind_refusal
    from medialaxis.core.outputs import method_kind

    if domain not in METHODS:
        return
    method = DEFAULT_METHOD[domain] if method is None else method
    kind = method_kind(domain, method)
    for out in outputs:
        reason = kind_refusal(out, kind)
        if reason is not None:
            where = f"-o {str(out)!r}" if source is None else f"--format {out.suffix[1:]} for {str(source)!r}"
            raise UsageError(f"{where}: the {domain} method {method!r} gives {kind}; {reason}")


def _summary(ma: Any) -> str:
    meta = ma.metadata
    parts = [
        f"method={meta.get('method')}",
        f"points={len(ma.points)}",
        f"edges={len(ma.edges)}",
        f"faces={len(ma.faces)}",
    ]
    if ma.dim == 2 or len(ma.faces) == 0:
        parts += [f"endpoints={len(ma.endpoints)}", f"junctions={len(ma.junctions)}", f"cycles={ma.n_cycles}"]
    parts.append(f"components={ma.n_components}")
    if meta.get("lam") is not None:
        parts.append(f"lam={meta['lam']:.4g}")
    if meta.get("thickness") is not None:
        parts.append(f"thickness={meta['thickness']:.4g}")
    if len(ma.radii):
        parts.append(f"radius=[{ma.radii.min():.4g}, {ma.radii.max():.4g}]")
    return " ".join(parts)


def add_compute(sub: Any) -> None:
    p = sub.add_parser(
        "compute",
        help="medial axis of shapes",
        description="Compute the medial axis of images, polygon files, meshes or volumes. Several inputs (files, "
                    "glob patterns, folders) write their outputs to --out-dir, one per --format, named after each "
                    "input; a folder of TIFF or DICOM slices is one volume, any other folder stands for its shape "
                    "files. A failing input is reported and the others are still done (exit 1 at the end).",
        formatter_class=HelpFormatter,
    )
    p.add_argument("input", type=Path, nargs="+",
                   help="image, SVG/GeoJSON/WKT, mesh or volume file, folder or glob pattern, or a saved result "
                        "(.json/.npz)")
    p.add_argument("-o", "--output", type=Path, action="append", default=[],
                   help=f"output file of a single input; the extension picks the format ({' '.join(WRITERS)}); "
                        f"one that cannot hold the method's kind of result ({limits_text()}) is refused before any "
                        f"work; {needs_text()}; repeatable")
    p.add_argument("--out-dir", type=Path, default=None, help="folder for the outputs of each input (created if needed)")
    p.add_argument("--format", default="json", help="output formats with --out-dir, comma-separated (e.g. json,svg), among "
                        + ",".join(w.lstrip(".") for w in WRITERS))
    p.add_argument("--method", default=None, metavar="METHOD",
                   help="method within the input's domain: " + "; ".join(
                       f"{domain} {', '.join(methods)} (default {DEFAULT_METHOD[domain]})" for domain, methods in METHODS.items()))
    methods = p.add_argument_group("method options", "generated from each method's options (docs/options.md); "
                                   "in brackets, the methods that take them")
    for name, flag, labels, hint in method_flags():
        methods.add_argument(flag.name or "--" + name.replace("_", "-"), help=f"{flag.help} [{', '.join(labels)}]",
                             **argument_kwargs(name, flag, hint))
    p.add_argument("--steps", type=Path, default=None,
                   help="save the pipeline stages: planar, one figure (PNG/SVG/PDF); volume, one mesh file per stage "
                        "named STEM_<k>_<stage>.<ext> (.ply .vtk .obj .json .npz)")
    p.add_argument("--frames", type=Path, default=None,
                   help="mesh flow: write each step to this folder (step_NNNN.ply and flow.html)")
    p.add_argument("--option", action="append", default=[], metavar="KEY=VALUE",
                   help="extra method option (value parsed as JSON when possible); repeatable")
    p.add_argument("--timings", action="store_true",
                   help="keep the wall-clock seconds of each stage in .json and .npz outputs (left out by default)")
    p.set_defaults(run=_run_compute)


def method_flags() -> list[tuple[str, Flag, list[str], Any]]:
    """Each method option's flag once (:func:`medialaxis.core.options.flags`), with the methods that take it."""
    from medialaxis._dispatch import option_types

    found = flags({f"{domain} {method}": cls for (domain, method), cls in option_types().items()})
    return [(name, flag, _domains(takers), hint) for name, flag, takers, hint in found]


def _domains(takers: list[str]) -> list[str]:
    """``["volume"]`` for ``["volume midsurface", "volume voxels"]``: a domain whose methods all take an option."""
    named = []
    for domain, methods in METHODS.items():
        mine = [f"{domain} {m}" for m in methods if f"{domain} {m}" in takers]
        named += [domain] if len(mine) == len(methods) else mine
    return named


def options_markdown() -> str:
    """``docs/options.md``: every method's options, from their dataclasses (``python -m medialaxis.cli.compute`` prints it)."""
    import dataclasses
    import re

    from medialaxis._dispatch import option_types, resolve
    from medialaxis.core.options import type_text

    lines = ["# Method options", "", "Generated from the options dataclasses (`src/medialaxis/*/options.py`) by",
             "`python -m medialaxis.cli.compute > docs/options.md`; `tests/test_options.py` checks it is current.",
             "Each option is a keyword of the method and of `medialaxis.medial_axis`, a field of the method's",
             "dataclass, and (where a flag is shown) a flag of `medialaxis compute`; any other option is",
             "`--option KEY=VALUE`.", ""]
    for (domain, method), cls in option_types().items():
        fn = resolve(domain, method)[1]
        lines += [f"## {domain}, method `{method}`", "",
                  f"`{fn.__module__}.{fn.__name__}`, options `{cls.__module__}.{cls.__name__}`", "",
                  "| option | type | default | flag | meaning |", "|---|---|---|---|---|"]
        for field in dataclasses.fields(cls):
            flag = field.metadata.get("flag")
            shown = "" if flag is None else f"`{flag.name or '--' + field.name.replace('_', '-')}`"
            text = re.sub(r":\w+:`~?([^`]+)`", r"`\1`", " ".join(field.metadata["doc"].split())).replace("|", "\\|")
            lines.append(f"| `{field.name}` | {type_text(cls, field)} | `{field.default!r}` | {shown} | {text} |")
        lines.append("")
    return "\n".join(lines)


def compute_options(args: argparse.Namespace) -> tuple[dict[str, Any], Any]:
    """Method options and spacing from the command line."""
    options: dict[str, Any] = dict(_parse_option(o) for o in args.option)
    for name, flag, _, _ in method_flags():
        value = getattr(args, name)
        if value is not None:
            try:
                options[name] = flag_value(name, flag, value)
            except ValueError as exc:
                raise UsageError(str(exc)) from None
    if options.get("n_jobs") is not None and options["n_jobs"] < 1:
        raise UsageError(f"--jobs must be at least 1, got {options['n_jobs']}")
    return options, options.pop("spacing", None)


def _run_batch(args: argparse.Namespace, inputs: list[Path]) -> int:
    """Each input computed and written on its own; failures reported per input."""
    import medialaxis as mx
    from medialaxis._progress import progress
    from medialaxis.cli.batch import output_names
    from medialaxis.core.io import WRITERS, output_batch

    if args.output:
        raise UsageError("-o names the output of one input; for several inputs use --out-dir DIR --format json,...")
    if args.steps is not None or args.frames is not None:
        raise UsageError("--steps and --frames take a single input")
    if args.out_dir is None:
        raise UsageError(f"{len(inputs)} inputs: give --out-dir DIR (and --format) for their outputs")
    formats = ["." + f.strip().lower().lstrip(".") for f in args.format.split(",") if f.strip()]
    unknown = [f for f in formats if f not in WRITERS]
    if unknown or not formats:
        raise UsageError(f"--format: unknown format(s) {', '.join(unknown) or '(none)'}; use some of "
                         f"{', '.join(w.lstrip('.') for w in WRITERS)}")
    if args.out_dir.exists() and not args.out_dir.is_dir():
        raise UsageError(f"--out-dir needs a folder, {str(args.out_dir)!r} is a file")
    plan = output_names(inputs, args.out_dir, formats)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    check_outputs(inputs, [out for outs in plan.values() for out in outs])
    for path in inputs:
        try:
            domain = mx._dispatch.classify(str(path), args.method)
        except MedialAxisError:
            continue  # reported in its turn
        if args.method is None or args.method in METHODS.get(domain, ()):
            check_kinds(plan[path], domain, args.method, source=path)
    options, spacing = compute_options(args)
    failed = 0
    for path in progress(inputs, desc="inputs"):
        try:
            ma = mx.medial_axis(str(path), method=args.method, spacing=spacing, **options)
            with output_batch():  # this input's outputs all appear, or none
                for out in plan[path]:
                    ma.save(out, timings=getattr(args, "timings", False))
        except MedialAxisError as exc:
            failed += 1
            _fail(f"{path}: {exc}")
            continue
        print(f"{path}: {_summary(ma)}")
        for out in plan[path]:
            print(f"wrote {out}")
    if failed:
        _fail(f"{failed} of {len(inputs)} inputs failed")
        return 1
    return 0


def _run_compute(args: argparse.Namespace) -> int:
    import medialaxis as mx
    from medialaxis.cli.batch import expand_inputs

    inputs = expand_inputs(args.input)
    if len(inputs) > 1 or args.out_dir is not None:
        return _run_batch(args, inputs)
    args.input = inputs[0]
    outputs = list(args.output) + ([args.steps] if args.steps else [])
    check_outputs([args.input], list(args.output))
    domain = mx._dispatch.classify(str(args.input), args.method)
    if args.method is not None and domain in METHODS and args.method not in METHODS[domain]:
        raise UsageError(
            f"--method {args.method!r} does not apply to {domain} input; choose one of {', '.join(METHODS[domain])}"
        )
    check_kinds(args.output, domain, args.method)
    if args.frames is not None:
        if domain != "mesh" or args.method != "flow":
            raise UsageError("--frames is available for meshes with --method flow")
        if args.frames.exists() and not args.frames.is_dir():
            raise UsageError(f"--frames needs a folder, {str(args.frames)!r} is a file")
        from medialaxis.core.io import check_writable

        check_writable(args.frames / "step_0001.ply" if args.frames.is_dir() else args.frames)
    if args.steps is not None:
        if domain == mx._dispatch.RESULT:
            raise UsageError("--steps needs a shape, not a saved result")
        if domain == "mesh":
            raise UsageError("--steps is available for planar and volume inputs")
        if domain == "planar":
            check_outputs([args.input], [args.steps], formats=(".png", ".svg", ".pdf"), option="--steps")
        else:
            check_outputs([args.input], [args.steps], option="--steps")
    options, spacing = compute_options(args)
    from medialaxis.core.io import output_batch

    # Every output appears at the end, or none does (a failure or Ctrl-C leaves nothing).
    with output_batch():
        if args.steps is not None and domain == "volume":
            from medialaxis.volume.steps import save_steps, stages_for_method

            stages = stages_for_method(str(args.input), args.method, spacing=spacing, **options)
            ma = stages.result
            outputs = list(args.output) + save_steps(stages, args.steps)
        elif args.steps is not None:
            from medialaxis.planar.pipeline import planar_stages
            from medialaxis.planar.plotting import save_stages_figure

            stages = planar_stages(str(args.input), spacing=spacing, **options)
            ma = stages.result
            save_stages_figure(stages, args.steps)
        else:
            writer = None
            if args.frames is not None:
                from medialaxis.mesh.skeleton.flow_frames import FrameWriter

                writer = options["callback"] = FrameWriter(args.frames)
            ma = mx.medial_axis(str(args.input), method=args.method, spacing=spacing, **options)
            if writer is not None:
                outputs += writer.finish()
        for out in args.output:
            ma.save(out, timings=getattr(args, "timings", False))
    print(f"{args.input}: {_summary(ma)}")
    for out in outputs:
        print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    print(options_markdown(), end="")
