"""The settings of ``persson-fast contact``: a TOML file (``--config``) and the flags, merged.

:func:`_resolve_contact` reads the TOML file, checks every key against the declared surface
model and the other settings, and lets the flags win; :func:`_make_surface` builds the
surface of the chosen model. An invalid setting raises :class:`CommandError`.
"""
from __future__ import annotations

import os
import tomllib

import numpy as np

from ..surfaces.models import SURFACE_MODELS
from .parser import (THEORY_NAMES, CommandError, _dest, _or, _selector_flags,
                         _surface_choices)


def _load_toml(path) -> dict:
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except OSError as exc:
        raise CommandError(f"cannot read --config {path!r}: {exc.strerror}") from None
    except tomllib.TOMLDecodeError as exc:
        raise CommandError(f"--config {path!r} is not valid TOML: {exc}") from None


def _number(value, key):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise CommandError(f"{key} must be a number; got {value!r}")
    return float(value)


def _boolean(value, key):
    """A TOML boolean (true or false); a string such as "yes" or a number is refused."""
    if not isinstance(value, bool):
        raise CommandError(f"{key} must be true or false (a TOML boolean, unquoted); got "
                           f"{value!r}")
    return value


def _text(value, key):
    if not isinstance(value, str):
        raise CommandError(f"{key} must be a string; got {value!r}")
    return value


#: the area theories whose pull-off stress ``--pull-off`` computes: persson_fast.pull_off
#: follows the contact branch of the scene's own theory (the corrected diffusions yp08 and
#: wm17 as well as the original; xu24 takes no adhesion, so its pull-off stress is 0), with
#: its yield wall where ``--hardness`` is given. The one place that refuses what it does
#: not serve (:func:`_refuse_unavailable_pull_off`).
PULL_OFF_THEORIES = ("persson01", "yp08", "wm17", "xu24")
#: whether ``--pull-off`` serves a yield wall (``--hardness``)
PULL_OFF_WITH_HARDNESS = True


def _refuse_unavailable_pull_off(settings: dict) -> None:
    """``--pull-off`` (or ``pull_off = true``) where the pull-off stress of the scene is not
    available: an area theory outside :data:`PULL_OFF_THEORIES`, or a yield wall while
    :data:`PULL_OFF_WITH_HARDNESS` is False."""
    if not settings["pull_off"]:
        return
    theory = settings["theory"].get("theory", "persson01")
    if theory not in PULL_OFF_THEORIES:
        raise CommandError(
            f"--pull-off is not available for --theory {theory}: the pull-off stress is "
            f"computed for {', '.join(PULL_OFF_THEORIES)} (it follows that theory's contact "
            f"branch, so beside --theory {theory} areas it would be another theory's number); "
            f"drop --pull-off, or use one of those theories")
    if settings["hardness"] is not None and not PULL_OFF_WITH_HARDNESS:
        raise CommandError(
            "--pull-off is not available with a yield wall: the pull-off stress is computed "
            "for elastic contact (without --hardness) only, so beside elastoplastic areas it "
            "would be the elastic scene's number; drop --pull-off or --hardness")


#: the spellings of the pressures' key in a TOML file (as --pressure and --pressures)
PRESSURE_KEYS = ("pressures", "pressure")


def _resolve_contact(args) -> dict:
    """Merge the TOML file (if any) and the flags (which win) into one settings dict."""
    cfg = _load_toml(args.config) if args.config else {}
    known_top = {"surface", "e_star", *PRESSURE_KEYS, "pressure_range", "method", "rtol", "csv",
                 "work_of_adhesion", "energy_correction", "detachment_prefactor", "pull_off",
                 "theory", "theory_gamma", "separation", "hardness", "hardness_exponent",
                 "gaps", "strict"}
    unknown = sorted(set(cfg) - known_top)
    if unknown:
        raise CommandError(f"unknown key(s) in --config: {', '.join(unknown)}; "
                           f"expected {', '.join(sorted(known_top))}")
    surf_cfg = cfg.get("surface", {})
    if not isinstance(surf_cfg, dict):
        raise CommandError("'surface' in --config must be a table ([surface])")
    surf_cfg = dict(surf_cfg)

    selectors = _selector_flags()
    from_flags = [name for name, (flag, _) in selectors.items()
                  if getattr(args, _dest(flag), None)]
    if len(from_flags) > 1 or (from_flags and args.surface):
        raise CommandError("give one of " + ", ".join(
            ["--surface", *(flag for flag, _ in selectors.values())]))
    model = (from_flags[0] if from_flags else None) or args.surface or surf_cfg.pop("model", None)
    surf_cfg.pop("model", None)
    if model is None:
        picks = [f"{flag} {'FILE' if p.path else p.metavar or 'VALUE'}"
                 for flag, p in selectors.values()]
        raise CommandError("no surface model: give " + _or(
            [f"--surface {{{','.join(_surface_choices())}}}", *picks])
            + ", or model = ... in the [surface] table of --config")
    if model not in SURFACE_MODELS:
        raise CommandError(
            f"surface model must be one of {', '.join(SURFACE_MODELS)}; got {model!r}")
    declared = SURFACE_MODELS[model].parameters
    keys = tuple(declared)
    unknown = sorted(set(surf_cfg) - set(keys))
    if unknown:
        raise CommandError(f"unknown [surface] key(s) for model {model!r}: {', '.join(unknown)}; "
                           f"expected {', '.join(keys)}")
    params = {k: _config_value(k, v, args.config, declared[k]) for k, v in surf_cfg.items()}
    own_flags = {p.flag_for(k) for k, p in declared.items()}
    for key, param in declared.items():
        value = getattr(args, _dest(param.flag_for(key)), None)
        if value is not None:
            params[key] = value
    # flags of the other models are an error, not silently ignored (a flag that picks a
    # model is the conflict above)
    stray = sorted({(k, p.flag_for(k)) for m in SURFACE_MODELS.values()
                    for k, p in m.parameters.items()
                    if not p.selects and p.flag_for(k) not in own_flags
                    and getattr(args, _dest(p.flag_for(k)), None) is not None})
    if stray:
        raise CommandError(f"{', '.join(flag for _, flag in stray)} do(es) not apply to surface "
                           f"model {model!r}")
    missing = [k for k in SURFACE_MODELS[model].required if k not in params]
    if missing:
        raise CommandError(f"surface model {model!r} needs " + ", ".join(
            f"{declared[k].flag_for(k)} (or {k} in [surface])" for k in missing))

    e_star = args.e_star if args.e_star is not None else cfg.get("e_star")
    if e_star is None:
        raise CommandError("no effective modulus: give --e-star E [Pa] (or e_star in --config)")
    e_star = _number(e_star, "e_star")

    if args.pressure is not None:
        pressure = np.asarray(args.pressure, dtype=float)
    elif args.pressure_range is not None:
        pressure = _pressure_range(*args.pressure_range)
    elif len([k for k in (*PRESSURE_KEYS, "pressure_range") if k in cfg]) > 1:
        given = [k for k in (*PRESSURE_KEYS, "pressure_range") if k in cfg]
        raise CommandError(f"--config gives {' and '.join(repr(k) for k in given)}; keep one "
                           f"('pressures' and 'pressure' are two spellings of one key)")
    elif any(k in cfg for k in PRESSURE_KEYS):
        key = next(k for k in PRESSURE_KEYS if k in cfg)
        raw = cfg[key]
        raw = raw if isinstance(raw, list) else [raw]
        if not raw:
            raise CommandError(f"{key} in --config must hold at least one nominal pressure "
                               f"[Pa]; got {cfg[key]!r}")
        pressure = np.asarray([_number(v, key) for v in raw], dtype=float)
    elif "pressure_range" in cfg:
        raw = cfg["pressure_range"]
        if not isinstance(raw, list) or len(raw) != 3:
            raise CommandError(f"pressure_range must be [pmin, pmax, n]; got {raw!r}")
        pressure = _pressure_range(*(_number(v, "pressure_range") for v in raw))
    else:
        raise CommandError("no pressures: give --pressure P [P ...] or "
                           "--pressure-range PMIN PMAX N "
                           "(or pressures / pressure_range in --config)")

    method = args.method or _text(cfg.get("method", "auto"), "method")
    rtol = args.rtol if args.rtol is not None else _number(cfg.get("rtol", 1e-6), "rtol")
    csv_path = _output_path(args.csv, cfg, "csv", "--csv")
    gaps_path = _output_path(getattr(args, "gaps", None), cfg, "gaps", "--gaps")
    adhesion = {}
    for key in ("work_of_adhesion", "energy_correction", "detachment_prefactor"):
        value = getattr(args, key)
        if value is None and key in cfg:
            value = _number(cfg[key], key)
        if value is not None:
            adhesion[key] = value
    want_pull_off = bool(args.pull_off or _boolean(cfg.get("pull_off", False), "pull_off"))
    want_separation = bool(args.separation
                           or _boolean(cfg.get("separation", False), "separation"))
    hardness = args.hardness
    if hardness is None and "hardness" in cfg:
        if isinstance(cfg["hardness"], dict):
            from ..plasticity.hardness import check_hardness
            try:
                hardness = check_hardness(cfg["hardness"], "hardness", scale_dependent=True)
            except ValueError as exc:
                raise CommandError(f"--config: {exc}") from None
        else:
            hardness = _number(cfg["hardness"], "hardness")
    exponent = args.hardness_exponent
    if exponent is None and "hardness_exponent" in cfg:
        exponent = _number(cfg["hardness_exponent"], "hardness_exponent")
    if exponent is not None:
        if not isinstance(hardness, float):
            raise CommandError(f"--hardness-exponent needs a constant --hardness (sigma_Y at "
                               f"zeta = 1) [Pa]; got hardness = {hardness!r}")
        from ..plasticity.hardness import hardness_power_law
        try:
            hardness = hardness_power_law(hardness, exponent)
        except ValueError as exc:
            raise CommandError(str(exc)) from None
    theory = {}
    name = args.theory or cfg.get("theory")
    if name is not None:
        name = _text(name, "theory")
    if name is not None:
        if name not in THEORY_NAMES:
            raise CommandError(f"theory must be one of {', '.join(THEORY_NAMES)}; got {name!r}")
        theory["theory"] = name
    gamma = args.theory_gamma
    if gamma is None and "theory_gamma" in cfg:
        gamma = _number(cfg["theory_gamma"], "theory_gamma")
    if gamma is not None:
        theory["theory_gamma"] = gamma
    settings = {"model": model, "params": params, "e_star": e_star, "pressure": pressure,
                "method": method, "rtol": rtol, "csv": csv_path, "adhesion": adhesion,
                "pull_off": want_pull_off, "theory": theory, "separation": want_separation,
                "hardness": hardness, "gaps": gaps_path,
                "strict": bool(getattr(args, "strict", False)
                               or _boolean(cfg.get("strict", False), "strict"))}
    _refuse_unavailable_pull_off(settings)
    _refuse_shared_files(settings, args.config)
    return settings


def _output_path(flag_value, cfg, key, flag):
    """An output file from its flag (which wins) or its key in --config; None when neither
    gives one; an empty name is refused (it would be no output at all, silently)."""
    if flag_value is not None:
        value, name = flag_value, flag
    elif key in cfg:
        value, name = _text(cfg[key], key), f"{key} in --config"
    else:
        return None
    if not value.strip():
        raise CommandError(f"{name} must name a file; got {value!r} (leave it out for no "
                           f"{key} file)")
    return value


def _same_file(a: str, b: str) -> bool:
    """Whether two paths name one file: the same path once links, '.', '..' and the case
    rules of the platform are resolved, or (both existing) the same inode (a hard link)."""
    def norm(path):
        return os.path.normcase(os.path.realpath(os.path.abspath(path)))

    if norm(a) == norm(b):
        return True
    try:
        return os.path.samefile(a, b)
    except OSError:          # one of them does not exist (yet): different names, not one file
        return False


def _refuse_shared_files(settings: dict, config_path) -> None:
    """Two outputs of one run that are one file (``--csv same.csv --gaps ./same.csv``, a
    link, another spelling) would leave only the one written last; an output that is one of
    the run's inputs (--config, --topography, --psd) would replace what was read. Both are
    refused before anything is solved."""
    outputs = [(flag, path) for flag, path in (("--csv", settings["csv"]),
                                               ("--gaps", settings["gaps"])) if path]
    inputs = [("--config", config_path)] if config_path else []
    for key, param in SURFACE_MODELS[settings["model"]].parameters.items():
        if param.path and isinstance(settings["params"].get(key), str):
            inputs.append((param.flag_for(key), settings["params"][key]))
    for i, (flag, path) in enumerate(outputs):
        for other, other_path in outputs[i + 1:]:
            if _same_file(path, other_path):
                raise CommandError(
                    f"{flag} and {other} name the same file ({path!r} and {other_path!r} are "
                    f"both {os.path.realpath(path)!r}): one would overwrite the other; give "
                    f"each output a file of its own")
        for other, other_path in inputs:
            if _same_file(path, other_path):
                raise CommandError(
                    f"{flag} names the input file of {other} ({path!r} is "
                    f"{os.path.realpath(other_path)!r}): writing it would replace what this "
                    f"run reads; give the output another file")


def _pressure_range(pmin, pmax, n) -> np.ndarray:
    if n != int(n) or n < 1:
        raise CommandError(f"the number of pressures N must be a whole number >= 1; got {n!r}")
    return np.linspace(float(pmin), float(pmax), int(n))


def _config_value(key, value, config_path, param):
    """A [surface] value as its declaration says: text (a relative file name is taken from the
    folder of the config file), a list of numbers, or a number."""
    if param.type is str:
        if not isinstance(value, str):
            raise CommandError(f"surface.{key} must be a string; got {value!r}")
        if param.path and config_path and not os.path.isabs(value):
            value = os.path.join(os.path.dirname(os.path.abspath(config_path)), value)
        return value
    if param.nargs:
        raw = value if isinstance(value, list) else [value]
        return [_number(v, f"surface.{key}") for v in raw]
    number = _number(value, f"surface.{key}")
    if param.type is int:
        if not number.is_integer():
            raise CommandError(f"surface.{key} must be a whole number; got {value!r}")
        return int(number)
    return number


def _make_surface(model: str, params: dict):
    """The surface of a declared model (``SURFACE_MODELS[model].build(**params)``); a
    ValueError that names a parameter as the API spells it (``q_unit=``, ``C_unit must``) is
    raised as a CommandError that names its flag (``--q-unit``, ``--c-unit``)."""
    declared = SURFACE_MODELS[model].parameters
    try:
        return SURFACE_MODELS[model].build(**params)
    except CommandError:
        raise
    except ValueError as exc:
        raise CommandError(_flag_names(str(exc), declared)) from None


def _flag_names(message: str, declared: dict) -> str:
    """``message`` with the API's keyword arguments of the model (``q_unit=``, a message
    that opens with ``C_unit must``, a quoted ```physical_sizes```) written as its
    command-line flags (``--q-unit``, ``--c-unit``, ``--physical-size``; in a TOML file the
    [surface] key keeps the API's name)."""
    import re

    for key, param in declared.items():
        flag = param.flag_for(key)
        message = re.sub(rf"(?<![\w.-]){re.escape(key)}=(?!=) ?", f"{flag} ", message)
        message = re.sub(rf"^{re.escape(key)}(?= must )", flag, message)
        message = message.replace(f"`{key}`", flag)
    return message
