# SPDX-License-Identifier: MIT
"""The methods' options as keyword arguments: name, type and the default the library takes
when the option is absent (docs/morph.md, untangle.md, fit.md, deform.md, optimize.md). None:
the method chooses (by the mesh's dimension, or the input's validity). Only the keywords a
caller passes go to the case's "options" (optimize's "boundary" as boundary_mode, beside
its boundary list); python/tests/test_options.py checks that passing
every default gives the run that passing none gives.
"""
import functools
import inspect

_SOLVER = ("solver", str, "auto")

MORPH = [
    ("method", str, "morph"), _SOLVER, ("tolerance", float, 1e-9), ("gradient_tolerance", float, 1e-12),
    ("eps0", float, 0.1), ("delta0", float, 1e-3), ("penalty0", float, 10.0), ("m0", float, 10.0),
    ("m_factor", float, 100.0), ("min_decrease", float, 0.0), ("weights", str, "adaptive"), ("alpha", float, 3.0),
    ("beta", float, 1.25), ("weight_growth", str, "adaptive"), ("max_weight", float, 1e12), ("max_outer", int, 40),
    ("max_weight_updates", int, 100), ("weight_steps", int, 4), ("max_newton", int, 200), ("exact_first", bool, True),
    ("guard", str, "auto"), ("finish", str, "untangle"), ("stiffening", float, 1.0), ("poisson_ratio", float, 0.3),
]
# The Morpher runs paper 000's method only: the baselines' keys are morph()'s.
MORPHER = [o for o in MORPH if o[0] not in ("method", "stiffening", "poisson_ratio")]
UNTANGLE = [
    ("n", float, -1.0), ("h_min", float, 0.75), ("eps_delta", float, 1e-6), ("alpha", float, 1.0), ("beta", float, 0.1),
    ("eps_q", float, 0.01), ("gamma_untangle", float, 0.5), ("gamma_smooth", float, 1.0), ("reference", str, None),
    ("delta_rule", str, "continuation"), ("predictor", bool, True), ("max_newton", int, 300), _SOLVER,
]
FIT = [
    ("metric", str, None), ("target", str, None), ("weight0", float, 0.0), ("penalty0", float, 1.0),
    ("weights", str, "adaptive"), ("alpha_sigma", float, 10.0), ("eps_dsigma", float, 1e-3), ("eps_sigma", float, None),
    ("n_sigma", int, 10), ("max_newton", int, 200), ("growth", float, 1.2), ("det_floor", float, 1e-3),
    ("flat_edges", bool, False), ("split", bool, True), ("level_set", str, "analytic"), ("materials", str, None),
    ("pillow", str, "auto"), ("features", bool, True), _SOLVER,
]
DEFORM = [
    ("method", str, "eikonal"), ("cvt", bool, True), ("density", str, "uniform"), ("cvt_tolerance", float, 1e-4),
    ("cvt_max_iterations", int, 5000), ("feature_angle", float, 30.0), ("alpha", float, 1.0), ("beta", float, 1.0),
    ("diffusion", str, "design"), ("convection", str, "advective"), ("eikonal_h", float, 1.0), ("max_newton", int, 40),
    _SOLVER,
]
OPTIMIZE = [
    ("metric", str, None), ("quadrature", str, "lobatto"), ("quadrature_degree", int, 0), ("target", str, "ideal"),
    ("boundary_mode", str, "fixed", "boundary"), ("feature_angle", float, 30.0), ("max_newton", int, 50), ("rtol", float, 1e-10),
    ("growth", float, 1.2), ("det_floor", float, 0.0), _SOLVER,
]


def keyword_options(spec, doc):
    """Gives `function` (which takes `options`, a dict) the options of `spec` as keyword-only
    arguments with their defaults in its signature; those a caller passes join `options`."""
    def decorate(function):
        signature = inspect.signature(function)
        keys = {entry[0]: entry[3] if len(entry) > 3 else entry[0] for entry in spec}
        parameters = list(signature.parameters.values()) + [
            inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=default,
                              annotation=kind if default is not None else f"{kind.__name__} | None")
            for name, kind, default, *_ in spec]

        @functools.wraps(function)
        def call(*args, **keywords):
            given = {keys[name]: keywords.pop(name) for name in keys if name in keywords}
            bound = signature.bind(*args, **keywords)
            if given:
                options = dict(bound.arguments.get("options") or {})
                for name, value in given.items():
                    if name in options:
                        raise TypeError(f"{function.__name__}() got option {name!r} both in options and as a keyword")
                    if value is not None:
                        options[name] = value
                bound.arguments["options"] = options
            return function(*bound.args, **bound.kwargs)

        call.__signature__ = signature.replace(parameters=parameters)
        call.__doc__ = (function.__doc__ or "") + "\n\n" + doc + " keyword options (docs): " + ", ".join(
            f"{name}={default!r}" for name, _, default, *_ in spec) + "; None: the method chooses."
        return call

    return decorate
