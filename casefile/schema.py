"""The one description of a case file: every section and key, its type, unit, default,
rule and which tool reads it. No physics and no numerics live here; each package turns
the validated dict into its own problem objects.

Tools: ``bem`` (``bem solve``) and ``fem`` (``fem-reference solve``). A section marked
``discretization`` belongs to one tool (``[grid]`` to the BEM, ``[fem]`` to the FEM) and
the other tool ignores it; any other key a tool does not read is an error for that tool,
never silently dropped.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .validation import KINDS, RULES, Key

__all__ = ["KINDS", "TOOLS", "RULES", "BOTH", "Key", "Variant", "Section", "SCHEMA", "section", "readers"]

#: the tools that read case files, and their command names
TOOLS = {"bem": "bem solve", "fem": "fem-reference solve"}
#: the readers of a key, variant or section that names none
BOTH = ("bem", "fem")
#: the BEM alone
BEM = ("bem",)


@dataclass(frozen=True)
class Variant:
    """The keys that one value of a section's selector key brings (a material model, an
    indenter shape), and the tools that can solve it."""

    name: str
    doc: str
    keys: tuple = ()
    readers: tuple = BOTH


@dataclass(frozen=True)
class Section:
    """A ``[section]`` of a case file.

    ``selector`` names the key whose value picks one of ``variants`` (its keys join the
    section's); ``one_of`` lists groups of keys of which exactly one must be given;
    ``required_by`` the tools that need the section.
    """

    name: str
    doc: str
    keys: tuple = ()
    readers: tuple = BOTH
    required_by: tuple = ()
    discretization: bool = False
    selector: str | None = None
    variants: dict = field(default_factory=dict)
    one_of: tuple = ()

    def key(self, name: str, variant: str | None = None) -> Key | None:
        """The key ``name`` of the section (with the keys of ``variant``), or ``None``."""
        keys = self.keys + (self.variants[variant].keys if variant in self.variants else ())
        return next((k for k in keys if k.name == name), None)

    def all_keys(self, name: str) -> list[Key]:
        """Every declaration of ``name`` in the section and its variants."""
        keys = list(self.keys) + [k for v in self.variants.values() for k in v.keys]
        return [k for k in keys if k.name == name]


def _radius(readers=BOTH) -> Key:
    return Key("radius", "number", "m", "radius R of the indenter", readers, required=True, rule=">0")


def _xy(name: str, kind: str, unit: str, doc: str, rule: str = ">0", default_doc: str = "") -> tuple:
    """A grid quantity given once for both directions or per direction."""
    return (
        Key(name, kind, unit, f"{doc}, both directions (or {name}_x and {name}_y)", ("bem",), rule=rule,
            default_doc=default_doc),
        Key(f"{name}_x", kind, unit, f"{doc} along x", ("bem",), rule=rule),
        Key(f"{name}_y", kind, unit, f"{doc} along y", ("bem",), rule=rule),
    )


SCHEMA: tuple = (
    Section(
        "layer", "the layer bonded to a rigid base at z = 0, free surface z = H",
        keys=(
            Key("thickness", "number", "m", "thickness H", required=True, rule=">0"),
            Key("density", "number", "kg/m^3", "density rho; 0 neglects inertia", default=0.0, rule=">=0"),
        ),
        required_by=BOTH,
    ),
    Section(
        "material", "the incompressible linear viscoelastic solid (SI units, G* at omega in rad/s)",
        keys=(Key("model", "string", "-", "material model", required=True,
                  choices=("elastic", "three_parameter", "prony", "table", "dma")),),
        required_by=BOTH,
        selector="model",
        variants={
            "elastic": Variant("elastic", "G*(omega) = G", (
                Key("shear_modulus", "number", "Pa", "shear modulus G", required=True, rule=">0"),)),
            "three_parameter": Variant(
                "three_parameter", "the paper's three-parameter solid, eq. 71", (
                    Key("G0", "number", "Pa", "static shear modulus G(0)", required=True, rule=">0"),
                    Key("tau", "number", "s", "creep time", required=True, rule=">0"),
                    Key("f", "number", "-", "G1/G2; glassy modulus G0 (1 + f)", required=True, rule=">=0"),
                )),
            "prony": Variant(
                "prony", "generalized Maxwell: G*(w) = G_inf + sum_i G_i i w tau_i / (1 + i w tau_i)", (
                    Key("G_inf", "number", "Pa", "relaxed modulus", required=True, rule=">0"),
                    Key("G", "numbers", "Pa", "branch moduli G_i", required=True, rule=">0"),
                    Key("tau", "numbers", "s", "branch relaxation times tau_i", required=True, rule=">0"),
                )),
            "table": Variant(
                "table", "a measured master curve (fem-reference refuses it: no time-domain form)", (
                    Key("file", "path", "-", "CSV with columns omega (rad/s), G' (Pa), G'' (Pa); "
                        "header line optional", required=True),
                )),
            "dma": Variant(
                "dma", "DMA isotherms shifted to a master curve and run at a service temperature "
                "(docs/materials.md; fem-reference: paste the series that bem dma FILE --print-material "
                "prints as model = \"prony\")", (
                    Key("file", "path", "-", "DMA CSV: temperature, frequency, storage and loss moduli "
                        "with their units in the header (docs/materials.md)", BEM, required=True),
                    Key("reference_temperature", "number", "K", "T_ref of the master curve and of the shift "
                        "law", BEM, required=True, rule=">0"),
                    Key("temperature", "number", "K", "service temperature T: G*(omega; T) = b_T "
                        "G*_ref(a_T omega)", BEM, rule=">0", default_doc="reference_temperature"),
                    Key("shift_law", "string", "-", "time-temperature shift law; fitted to the isotherms' "
                        "overlap unless its constants are given", BEM, default="wlf", choices=("wlf", "arrhenius")),
                    Key("C1", "number", "-", "WLF C1 (with C2): log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref)",
                        BEM, rule=">0", default_doc="fitted"),
                    Key("C2", "number", "K", "WLF C2 (with C1); the law holds only above T_ref - C2", BEM,
                        rule=">0", default_doc="fitted"),
                    Key("activation_energy", "number", "J/mol", "Arrhenius E_a: log10 a_T = E_a / (R ln 10) "
                        "(1/T - 1/T_ref)", BEM, rule=">0", default_doc="fitted"),
                    Key("vertical", "string", "-", "vertical shift b_T: T rho / (T_ref rho_ref) from the CSV's "
                        "density_kg_m3 column, or fitted by overlap", BEM, choices=("density", "fit"),
                        default_doc="none (b_T = 1)"),
                    Key("form", "string", "-", "what the solve uses: the passive Prony series fitted at T_ref "
                        "and shifted (smooth, Kramers-Kronig consistent, tends to the rubbery and glassy "
                        "plateaus outside the data), or the shifted points binned into a table "
                        "(the data as measured, unphysical beyond them)", BEM, default="prony",
                        choices=("prony", "table")),
                    Key("terms_per_decade", "number", "-", "Prony relaxation times per decade of the data "
                        "(form = \"prony\")", BEM, default=2.0, rule=">0"),
                    Key("fit_tolerance", "number", "-", "largest relative error of G' and G'' the Prony fit "
                        "may leave at a data point (form = \"prony\")", BEM, rule=">0",
                        default_doc="none (bem dma reports the errors)"),
                    Key("extrapolate", "bool", "-", "accept a case whose frequency band omega = nu_x V "
                        "(2 pi V / L_x to pi V / spacing_x) leaves the data's range at temperature", BEM,
                        default_doc="false: such a case is an error"),
                ), readers=BEM),
        },
    ),
    Section(
        "indenter", "the rigid indenter",
        keys=(Key("shape", "string", "-", "indenter shape", default="sphere",
                  choices=("sphere", "paraboloid", "cylinder", "heightmap", "line")),),
        required_by=BOTH,
        selector="shape",
        variants={
            "sphere": Variant("sphere", "exact sphere, paper eq. 13", (_radius(),)),
            "paraboloid": Variant("paraboloid", "s = r^2 / (2 R)", (_radius(),)),
            "cylinder": Variant("cylinder", "roller of finite length with its axis along y: flat, rounded or "
                                "crowned ends (fem-reference: 3D rolling, [fem] model = \"3d\")", (
                _radius(),
                Key("length", "number", "m", "the roller's length L along y", required=True, rule=">0"),
                Key("edge_radius", "number", "m", "radius r_e of the rounding that blends the cylinder "
                    "tangentially into each end face, <= length / 2 and < radius; 0 is a flat-ended "
                    "cylinder", default=0.0, rule=">=0"),
                Key("crown_radius", "number", "m", "crowned roller instead: the generating line is one arc "
                    "of radius R_c >= length / 2 (drop y^2 / 2 R_c); not with edge_radius", rule=">0"),
            )),
            "line": Variant("line", "plane strain: a rigid cylinder of radius R with its axis along y, in "
                            "line contact; [loading] load is then per unit length along y (N/m)",
                            (_radius(),)),
            "heightmap": Variant("heightmap", "a measured or computed surface", (
                Key("file", "path", "-", "NPZ with arrays x (m, Kx), y (m, Ky), h (m, Ky x Kx): the gap "
                    "of the unloaded surface below the lowest point, >= 0", ("bem",), required=True),
            ), readers=("bem",)),
        },
    ),
    Section(
        "loading", "steady motion in +x and the normal loading (exactly one of load and indentation)",
        keys=(
            Key("speed", "number", "m/s", "speed V of the frame in +x; 0 is stationary contact",
                default=0.0, rule=">=0"),
            Key("load", "number", "N", "normal load P (load control)", rule=">0"),
            Key("indentation", "number", "m", "indentation d (displacement control)", rule=">0"),
        ),
        required_by=BOTH,
        one_of=(("load", "indentation"),),
    ),
    Section(
        "grid", "the BEM discretization (paper sections 7-8); nodes at x = i a, centred on the indenter",
        keys=(
            *_xy("spacing", "number", "m", "node spacing a"),
            *_xy("period", "number", "m", "period L of the Fourier series; need not be a multiple of a"),
            *_xy("truncation", "integer", "-", "truncation order Nt: modes |m|, |n| <= Nt"),
            *_xy("half_width", "number", "m", "candidate region |x|, |y| <= half_width",
                 default_doc="sized from an elastic estimate of the contact radius"),
        ),
        readers=("bem",),
        required_by=("bem",),
        discretization=True,
    ),
    Section(
        "friction", "Coulomb friction at the contact (absent: frictionless); needs speed > 0; with shape = "
        "\"line\" solved in plane strain, forces per unit length (N/m)",
        keys=(
            Key("mu", "number", "-", "coefficient of sliding friction", ("bem",), required=True, rule=">=0"),
            Key("mode", "string", "-", "loading mode: Q at the top (T = Q R, eq. 4), Q at the axle (T = 0), "
                "axle torque (Q = 0), or Omega given", ("bem",), default="pushed_at_top",
                choices=("pushed_at_top", "towed", "torque", "omega")),
            Key("omega", "number", "rad/s", "rotational speed Omega, mode = \"omega\" only; > 0 forward "
                "rolling, 0 pure sliding", ("bem",)),
            Key("radius", "number", "m", "axis to lowest point, for heightmap indenters", ("bem",),
                rule=">0", default_doc="the indenter's radius"),
            Key("kinematics", "string", "-", "rolling geometry: the indenter's exact surface for the gap, the "
                "normal forces' arm and the rolling radius (consistent energy balance); all to first order "
                "in the slope (a sphere as the paraboloid; consistent); or the paper's eq. 14 with the arm "
                "x / R on the exact sphere (reproduces its figures; R_r about r^2 / 2R^2 below the energy "
                "figure)", ("bem",), default="paper", choices=("exact", "small_slope", "paper")),
            Key("max_iter", "integer", "-", "active-set iterations allowed", ("bem",), default=300, rule=">0"),
            Key("direction_tol", "number", "-", "convergence of the slip law", ("bem",), default=1e-7, rule=">0"),
            Key("set_tol", "number", "-", "accepted stick/slip border violation in a two-state cycle",
                ("bem",), default=1e-2, rule=">=0"),
            Key("dense_limit", "integer", "-", "unknowns (3 per contact node) solved by dense LU; above, "
                "GMRES with FFT products (O(N) memory); a line contact takes dense LU up to 3000 contact nodes "
                "whatever this is", ("bem",), default=600, rule=">=0"),
        ),
        readers=("bem",),
    ),
    Section(
        "fem", "the fem_reference discretization (a_est: the estimated contact radius)",
        keys=(
            Key("model", "string", "-", "axisymmetric (r, z) section, 3D quarter cylinder, or the plane-strain "
                "(x, z) section of a line contact (steady rolling at [loading] speed)", ("fem",),
                choices=("axisymmetric", "3d", "plane_strain"),
                default_doc="plane_strain for a line indenter, axisymmetric otherwise"),
            Key("element_size", "number", "m", "element size in the contact zone", ("fem",), rule=">0",
                default_doc="axisymmetric min(a_est/24, H/4), 3d min(a_est/8, H/2), plane_strain "
                            "min(b_est/30, H/8) (b_est: the relaxed half-width)"),
            Key("contact_zone", "number", "m", "radius (plane strain: half-width) of the refined candidate "
                "contact zone", ("fem",), rule=">0", default_doc="1.4 a_est; plane_strain 1.5 b_est"),
            Key("domain_radius", "number", "m", "lateral extent of the truncated layer (3D rolling: the half box's extent in y; not plane_strain)",
                ("fem",), rule=">0", default_doc="contact_zone + 8 H; 3D rolling contact_zone + max(6 H, 4 a_est)"),
            Key("upstream", "number", "m", "rolling (plane strain, 3D): length ahead of the indenter (+x), where the "
                "material enters undeformed and relaxed; at least contact_zone + 2 max(H, b_est); the 3D half "
                "box extends max(upstream, downstream) both ways", ("fem",), rule=">0",
                default_doc="contact_zone + max(8 H, 6 b_est); 3D contact_zone + max(6 H, 4 a_est)"),
            Key("downstream", "number", "m", "rolling (plane strain, 3D): length behind the indenter (-x), where the material "
                "leaves; at least contact_zone + 2 max(H, b_est) + 3 V t_r (t_r the longest creep time)",
                ("fem",), rule=">0", default_doc="contact_zone + max(8 H, 6 b_est, 8 V t_r); 3D contact_zone + max(6 H, 4 a_est, 6 V t_r)"),
            Key("far_size", "number", "m", "largest element size", ("fem",), rule=">0",
                default_doc="H/2 axisymmetric and plane_strain (along x behind the indenter at least V t_r/4), "
                            "H in 3d"),
            Key("grading", "number", "-", "size growth with distance from the zone", ("fem",), default=0.3,
                rule=">0"),
            Key("refine", "integer", "-", "uniform refinements of the mesh (nested levels)", ("fem",),
                default=0, rule=">=0"),
            Key("solver", "string", "-", "sparse LU, or MINRES with AMG (needs the minres extra: pyamg)",
                ("fem",), default="direct", choices=("direct", "minres")),
            Key("rtol", "number", "-", "MINRES relative tolerance", ("fem",), default=1e-8, rule=">0"),
            Key("fit_nodes", "integer", "-", "surface vertices outside the edge fitted for the radius "
                "(>= 2)", ("fem",), default=3, rule=">0"),
            Key("max_iterations", "integer", "-", "active-set iteration limit", ("fem",), default=100,
                rule=">0"),
        ),
        readers=("fem",),
        discretization=True,
    ),
)


def section(name: str) -> Section | None:
    """The section called ``name``, or ``None``."""
    return next((s for s in SCHEMA if s.name == name), None)


def readers(key: Key) -> tuple:
    """The tools that read ``key``: those it names, else both (its section and variant
    say which of them read the table at all)."""
    return key.readers or BOTH
