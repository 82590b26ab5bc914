"""The rolling kinematics of docs/derivations.md ("Rolling kinematics"), checked with
sympy: a rigid body of revolution about the ``y`` axis turning at ``Omega``, its radial
normal forces, and the energy balance of the frictional equilibrium for each choice of
``[friction] kinematics``."""

import sympy as sp

x, y, R, V, Om = sp.symbols("x y R V Omega", positive=True)
N, Sx, Sy, ux, vx, slope, arm, ell = sp.symbols("N S_x S_y u_x v_x g_x arm ell", real=True)
rho = sp.Function("rho", positive=True)(y)  # the body's radius at y (R - e(y)); a sphere: sqrt(R^2 - y^2)
D = sp.sqrt(rho**2 - x**2)   # depth of the surface point below the axis
g = R - D                    # the gap profile above the lowest point (rho(0) = R)


def test_surface_speed_and_normal_force_arm_of_a_body_of_revolution():
    omega = sp.Matrix([0, Om, 0])  # clockwise with +x right and +z up: forward rolling
    r = sp.Matrix([x, y, -D])      # a surface point relative to the centre
    v = omega.cross(r)
    # the horizontal surface speed is Omega times the depth D = R - g: the rolling radius
    assert sp.simplify(v[0] + Om * (R - g)) == 0
    # a radial force (through the centre, no moment) with vertical component N on the body
    f = -N * r / D
    assert sp.simplify(f[2] - N) == 0 and sp.simplify(r.cross(f)) == sp.zeros(3, 1)
    # its horizontal part is -N x / D: the arm x / D is the profile slope dg/dx
    assert sp.simplify(-f[0] / N - sp.diff(g, x)) == 0
    # and the paper's l(y) = sqrt(R^2 - y^2) is the distance from the axis, not the depth
    assert sp.simplify(sp.sqrt(x**2 + D**2) - rho) == 0


def test_relative_velocity_along_the_normal_is_second_order():
    """Layer particle (moving frame) against the body's surface point: their difference
    has no normal part at zero strain, so the normal force's horizontal part does no work."""
    layer = sp.Matrix([-V * (1 + ux), -V * vx, -V * sp.diff(g, x)])  # surface follows the body
    body = sp.Matrix([-Om * D, 0, -Om * x])
    normal = sp.Matrix([x, y, -D])
    rel = sp.expand(sp.simplify((body - layer).dot(normal)))
    assert sp.simplify(rel - V * (ux * x + vx * y)) == 0


def test_energy_balance_closes_when_the_arm_is_the_slope():
    """R_r V - P_visc - P_fric = V N (arm - g_x) per node, whatever ell (eqs. 1, 2, 63)."""
    Q = N * arm + Sx               # horizontal equilibrium
    T = -ell * Sx                  # moment about the axle
    wx, wy = V * (1 + ux) - Om * ell, V * vx
    p_visc = V * N * slope - V * (Sx * ux + Sy * vx)  # -V t . du/dx, w_x up = g_x in contact
    p_fric = Sx * wx + Sy * wy
    assert sp.simplify(Q * V + T * Om - p_visc - p_fric - V * N * (arm - slope)) == 0


def test_each_choice_arm_against_its_profile_slope():
    sphere = {rho: sp.sqrt(R**2 - y**2)}
    # exact: arm x / D on the exact sphere
    assert sp.simplify((sp.diff(g, x) - x / D).subs(sphere).doit()) == 0
    # small_slope: the paraboloid (x^2 + y^2) / 2R with arm x / R
    assert sp.diff((x**2 + y**2) / (2 * R), x) == x / R
    # paper: arm x / R on the exact sphere misses the slope by -x r^2 / 2R^3 (+ higher order)
    miss = (x / R - sp.diff(g, x)).subs(sphere).doit()
    series = sp.series(miss.subs({x: sp.Symbol("t") * x, y: sp.Symbol("t") * y}), sp.Symbol("t"), 0, 5).removeO()
    assert sp.simplify(series.subs(sp.Symbol("t"), 1) + x * (x**2 + y**2) / (2 * R**3)) == 0
