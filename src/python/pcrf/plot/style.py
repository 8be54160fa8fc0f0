"""How figures look: readable fonts, the Okabe–Ito colour-blind-safe palette, labels with units."""
import matplotlib

from .. import _names as schema

# Okabe & Ito (2008), distinguishable under the common colour-vision deficiencies.
BLACK, ORANGE, SKY_BLUE, GREEN, YELLOW, BLUE, VERMILLION, PURPLE = (
    "#000000", "#E69F00", "#56B4E9", "#009E73", "#F0E442", "#0072B2", "#D55E00", "#CC79A7")
CYCLE = [BLUE, ORANGE, GREEN, VERMILLION, PURPLE, SKY_BLUE, YELLOW, BLACK]
GREY = "#8C8C8C"

# Colours of the statuses the engine names (`pcrf settings --json`); a status added to the
# engine later gets its kind's colour (survived, collapse, no verdict).
STATUS_COLOURS = {
    "at_rest": GREEN,
    "rocking_at_end": SKY_BLUE,
    "tendon_fracture": VERMILLION,
    "overturned": PURPLE,
    "solver_failure": BLACK,
    "time_limit": ORANGE,
    "invalid_frame": GREY,
    "not_run": "#E5E5E5",
}
KIND_COLOURS = {"survived": BLUE, "collapse": VERMILLION, "no_verdict": YELLOW}


def status_colour(name, kind):
    return STATUS_COLOURS.get(name, KIND_COLOURS.get(kind, GREY))


# Display symbols of the frame parameters and axes (the engine's names are the keys; a name
# without a symbol is shown as it is).
PARAMETER_SYMBOLS = {
    "kappa": r"$\kappa$", "lambda": r"$\lambda$", "tan_alpha": r"$\tan\alpha$", "lambda_h": r"$\lambda_h$",
    "pi_sigma_b": r"$\Pi_{\sigma b}$", "pi_sigma_c": r"$\Pi_{\sigma c}$", "pi_e_b": r"$\Pi_{Eb}$",
    "pi_e_c": r"$\Pi_{Ec}$", schema.SCALE: "scale factor", schema.RECORD: schema.RECORD, schema.CASE: schema.CASE,
}

# Labels of the metrics a figure shows most (others: the cube's long name and units).
METRIC_LABELS = {
    schema.THETA_MAX: r"peak $|\theta_1|$ [rad]",
    schema.OMEGA_MAX: r"peak $|\dot\theta_1|$ [rad/s]",
    schema.STRAIN_COLUMN_MAX: "peak column tendon strain [–]",
    schema.STRAIN_BEAM_MAX: "peak beam tendon strain [–]",
    schema.IMPACTS: "impacts [–]",
    schema.T_THETA_MAX: r"time of peak $|\theta_1|$ [s]",
    schema.CPU_TIME: "CPU time per case [s]",
}


def apply():
    matplotlib.rcParams.update({
        "font.size": 11, "axes.titlesize": 12, "axes.labelsize": 11, "legend.fontsize": 9,
        "xtick.labelsize": 10, "ytick.labelsize": 10, "axes.prop_cycle": matplotlib.cycler(color=CYCLE),
        "axes.grid": True, "grid.alpha": 0.3, "figure.dpi": 110, "savefig.dpi": 150,
        "svg.hashsalt": "pcrf",  # stable SVG ids
    })


def pretty_units(units):
    return {"1": "–", "rad s-1": "rad/s", "m/s2": "m/s²", "m s-1": "m/s"}.get(units, units)


def metric_label(name, variable=None):
    if name in METRIC_LABELS:
        return METRIC_LABELS[name]
    if variable:
        return f"{variable['long_name']} [{pretty_units(variable['units'])}]"
    return name


def parameter_label(name):
    symbol = PARAMETER_SYMBOLS.get(name, name)
    return symbol if name in (schema.RECORD, schema.CASE, schema.SCALE) else f"{symbol} [–]"


def intensity_label(cube, units):
    """ "peak ground acceleration [g]" from the cube's intensity variable, else "intensity [units]"."""
    variable = cube.variable(schema.IDA_INTENSITY)
    name = variable["long_name"].split(": ", 1)[-1] if variable else schema.INTENSITY
    return f"{name} [{pretty_units(units)}]"
