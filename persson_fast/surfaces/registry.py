"""The registry of surface models: declared parameters (:class:`Parameter`), a model as the
command line and :func:`persson_fast.scan` see it (:class:`SurfaceModel`), and
:data:`SURFACE_MODELS`, filled by :func:`register_surface_model`.

A :class:`~persson_fast.surfaces.models.Surface` subclass that sets ``MODEL`` registers itself when it
is created (``Surface.__init_subclass__``); the measured-surface models ('topography', 'psd')
are registered in :mod:`persson_fast.surfaces.tabulated`. The ``persson-fast contact`` command builds its
flags and TOML keys from this registry. All names here are re-exported by
:mod:`persson_fast.surfaces`.
"""
from __future__ import annotations

import inspect
from dataclasses import dataclass

__all__ = [
    "Parameter",
    "SurfaceModel",
    "SURFACE_MODELS",
    "BAND",
    "band_parameters",
    "register_surface_model",
]


# ----------------------------------------------------------------------------------------------
# declared parameters and the registry of surface models
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Parameter:
    """One declared parameter of a surface model.

    Parameters
    ----------
    unit : str or None
        SI unit of the value as the model takes it ('m', '1/m', 'J/m^2', '-' for a
        dimensionless number); None for text (file names, unit names), counts and values in a
        unit chosen by another parameter. The command line's help shows it in brackets, and
        :func:`persson_fast.scan` labels its axes with it.
    help : str
        What the parameter is, without the unit (e.g. 'rms height').
    required : bool, optional
        Whether the model needs it (default False). [-]
    metavar : str, optional
        The value's name in the command line's help; default the parameter's name in capitals.
    flag : str, optional
        The command-line flag; default ``--`` and the name in lower case with '-' for '_'
        (``h_rms`` -> ``--h-rms``, ``C0`` -> ``--c0``).
    type : {float, int, str}, optional
        The type of the value (default float); str for text, which TOML must give as a string.
    nargs : str, optional
        '+' for a list of numbers (argparse's nargs); default one value.
    path : bool, optional
        A file name: in a TOML file taken relative to the TOML file's folder (default False).
    selects : bool, optional
        Its flag also picks the model (``--psd FILE``); such a model is not one of the choices
        of ``--surface`` (default False).

    Notes
    -----
    The default a model uses when a parameter is not given is its constructor's (the help
    shows it, read from the signature); every flag's own default is "not given".
    """

    unit: str | None
    help: str
    required: bool = False
    metavar: str | None = None
    flag: str | None = None
    type: type = float
    nargs: str | None = None
    path: bool = False
    selects: bool = False

    def flag_for(self, name: str) -> str:
        """The command-line flag of the parameter ``name``."""
        return self.flag or "--" + name.lower().replace("_", "-")


@dataclass(frozen=True)
class SurfaceModel:
    """A surface model as the command line and :func:`persson_fast.scan` see it.

    Parameters
    ----------
    name : str
        The model's name: ``--surface NAME``, ``model = 'NAME'`` in a TOML file.
    parameters : dict of str to Parameter
        The keyword arguments of ``build`` the model offers, in the order shown.
    build : callable
        ``build(**values)`` returns the :class:`Surface`; it gets the parameters that were
        given, no others.
    title : str
        Title of the model's group of flags in the command line's help.
    description : str, optional
        Text under that title.
    """

    name: str
    parameters: dict
    build: object
    title: str
    description: str | None = None

    @property
    def required(self) -> tuple:
        """Names of the parameters the model needs."""
        return tuple(k for k, p in self.parameters.items() if p.required)

    @property
    def selector(self):
        """Name of the parameter whose flag picks the model, or None."""
        return next((k for k, p in self.parameters.items() if p.selects), None)

    def defaults(self) -> dict:
        """The defaults ``build`` uses for the parameters it has one for (not None)."""
        try:
            sig = inspect.signature(self.build)
        except (TypeError, ValueError):
            return {}
        return {k: v.default for k, v in sig.parameters.items()
                if k in self.parameters and v.default is not inspect.Parameter.empty
                and v.default is not None}


#: the surface models by name, in the order they were registered (the package's own first:
#: capillary, self-affine, topography, psd)
SURFACE_MODELS: dict = {}

#: names of the band limits every model has; the command line lists their flags once
BAND = ("q0", "q1")

_MODEL_NAME_CHARS = frozenset("abcdefghijklmnopqrstuvwxyz0123456789-")


def band_parameters(required: bool = True) -> dict:
    """The declarations of the band limits q0 and q1 (for a model's ``PARAMETERS``).

    Parameters
    ----------
    required : bool, optional
        Whether the model needs them (default True); measured spectra have their own. [-]
    """
    return {"q0": Parameter("1/m", "smallest wavevector", required=required),
            "q1": Parameter("1/m", "largest wavevector", required=required)}


def register_surface_model(model: SurfaceModel) -> SurfaceModel:
    """Add ``model`` to :data:`SURFACE_MODELS` (a model of the same name and the same build
    replaces it: a module imported again); return it.

    A :class:`Surface` subclass that sets ``MODEL`` is registered when it is created; call this
    for a model built by another function (as ``TabulatedPSD.from_file`` for 'psd').

    Raises
    ------
    ValueError
        For a name that is not lower-case letters, digits and '-', a name another model
        has, a parameter that is not a :class:`Parameter` or not a keyword of ``build``, more
        than one parameter that ``selects``, or a flag another model declares with another
        type or number of values.
    """
    if not isinstance(model, SurfaceModel):
        raise ValueError(f"model must be a SurfaceModel; got {type(model).__name__}")
    name = model.name
    if not isinstance(name, str) or not name or not set(name) <= _MODEL_NAME_CHARS \
            or name.startswith("-"):
        raise ValueError(f"a surface model name must be lower-case letters, digits and '-' "
                         f"(a command-line choice); got name = {name!r}")
    old = SURFACE_MODELS.get(name)
    if old is not None and _origin(old.build) != _origin(model.build):
        raise ValueError(f"surface model {name!r} is registered already (built by "
                         f"{_origin(old.build)}); choose another name")
    if not isinstance(model.parameters, dict):
        raise ValueError(f"parameters of surface model {name!r} must be a dict of name to "
                         f"Parameter; got {type(model.parameters).__name__}")
    try:
        sig = inspect.signature(model.build)
        takes = None if any(p.kind is inspect.Parameter.VAR_KEYWORD
                            for p in sig.parameters.values()) else set(sig.parameters)
    except (TypeError, ValueError):
        takes = None
    for key, p in model.parameters.items():
        if not isinstance(p, Parameter):
            raise ValueError(f"parameter {key!r} of surface model {name!r} must be a Parameter; "
                             f"got {p!r}")
        if not isinstance(key, str) or not key.isidentifier():
            raise ValueError(f"parameter names of surface model {name!r} must be identifiers "
                             f"(keyword arguments); got {key!r}")
        if takes is not None and key not in takes:
            raise ValueError(f"parameter {key!r} of surface model {name!r} is not a keyword "
                             f"argument of its build {_origin(model.build)}")
        flag = p.flag_for(key)
        for other in SURFACE_MODELS.values():
            if other.name == name:
                continue
            for okey, op in other.parameters.items():
                if op.flag_for(okey) == flag and (op.type, op.nargs) != (p.type, p.nargs):
                    raise ValueError(
                        f"flag {flag} of surface model {name!r} (parameter {key!r}) is "
                        f"declared by model {other.name!r} with type {op.type.__name__}, "
                        f"nargs {op.nargs!r}; got type {p.type.__name__}, nargs {p.nargs!r}")
    if sum(p.selects for p in model.parameters.values()) > 1:
        raise ValueError(f"surface model {name!r} may have one parameter that selects it; got "
                         f"{', '.join(k for k, p in model.parameters.items() if p.selects)}")
    SURFACE_MODELS[name] = model
    return model


def _origin(build) -> str:
    inner = getattr(build, "__func__", build)
    return f"{getattr(inner, '__module__', '?')}.{getattr(inner, '__qualname__', repr(inner))}"
