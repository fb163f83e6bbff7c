"""A floating vessel in six degrees of freedom as an FMI 2.0 Co-Simulation FMU (pythonfmu), to couple
riser to in libcosim through both of its ports (issue 30; docs/coupling.md "The vessel in six
degrees of freedom"). osp/vessel/Vessel.py, the heave-only body of issue 29, stays as it is: its
parameters mean other things (`mass` is M + A there) and its tests pin its numbers.

Frames and names are riser's (docs/theory.md §14): z up, x to the bow, y to port; the pose is the
reference point's displacement (surge, sway, heave; global) and the Euler angles roll φ, pitch θ,
yaw ψ under z-y-x, R = Rz(ψ) Ry(θ) Rx(φ) (vessel frame to global); the translational velocity is
global, the angular velocity (p, q, r) is in the vessel frame. The outputs carry exactly the names
of riser's inputs, so each connects one to one.

Model: linear seakeeping about the reference point, which is the centre of gravity, the centre of
rotation and above the waterplane's centroid (no heave-pitch or sway-roll coupling), all matrices
diagonal:

    (m + A_i) dν_i/dt = τ_i − B_i ν_i − C_i η_i            i = 1..6
    ν = (u, v, w, p, q, r),  η = (x, y, z, φ, θ, ψ)

with τ = (F, Rᵀ M + M_b) + wave excitation, F and M the riser's force and its moment about the
reference point (global: inputs top_force_*, top_moment_*; or M_b in the vessel frame: inputs
vessel_moment_*, the angular port's torque), less their values at the start when
`balance_initial_load` (the vessel trimmed and moored for the line as it hangs at t = 0: the
riser's weight on its ballast, its horizontal pull on the moorings' pre-tension). Restoring:
C33 = ρ g A_wp, C44 = ρ g ∇ GM_T, C55 = ρ g ∇ GM_L (hydrostatics), C11, C22, C66 station-keeping
springs (moorings or DP). The angles follow p, q, r through the exact z-y-x kinematics

    φ' = p + (q sin φ + r cos φ) tan θ,  θ' = q cos φ − r sin φ,  ψ' = (q sin φ + r cos φ)/cos θ

so the pose handed to riser is the integral of the angular velocity handed to it (riser's
velocity-driven path and its displacement path see the same vessel); at small angles these are
φ' = p, θ' = q, ψ' = r to first order, and the model is the linear one. Left out (small-angle
linear dynamics): gyroscopic and Coriolis terms, the frame of the added mass and damping (taken as
the global frame for translation, the vessel frame for rotation), second-order wave forces.

Wave excitation (wave frequency, regular): wave_force_x/y/z (global) and wave_moment_x/y/z (vessel
frame) amplitudes, each times r(t) sin(2π t / wave_period + phase_i), r(t) = ½(1 − cos(π t/ramp))
for t < ramp, 1 after.

Integrator: classical RK4 at sub-steps of at most `max_substep` (5 ms) inside each communication
step, the inputs held over the step. Besides the pose and velocities, the FMU reports `work`:
the work of the riser's held force and moment on the vessel, F·Δr + M·Δθ + M_b·Δθ_b over each
step (Δθ, Δθ_b the integrals of the angular velocity over the step, global R ω_b and vessel-frame
ω_b, integrated with the rest), and
`work_magnitude`, the sum of the magnitudes of each step's work (for ECCO's energy check).

Defaults: a 100 m supply-type vessel, L 100 m, B 20 m, T 6 m, C_B 0.70, C_WP 0.80:
  ∇ = 8400 m³, m = ρ∇ = 8.61e6 kg (ρ 1025 kg/m³, g 9.81 m/s²), A_wp = 1600 m²,
  radii of gyration 0.35 B = 7 m (roll), 0.25 L = 25 m (pitch, yaw):
  I44 = 4.219e8, I55 = I66 = 5.381e9 kg m²;
  added mass A11 0.05 m, A22 0.8 m, A33 1.0 m, A44 0.25 I44, A55 1.0 I55, A66 0.7 I66;
  C33 = ρ g A_wp = 1.609e7 N/m, C44 = ρ g ∇ GM_T (GM_T 2 m) = 1.689e8 N m/rad,
  C55 = ρ g ∇ GM_L (GM_L 120 m) = 1.014e10 N m/rad;
  natural periods: heave 6.5 s, roll 11.1 s, pitch 6.5 s;
  station keeping: C11 = C22 = 3.6e4 N/m and C66 = 2.0e7 N m/rad, periods about 100 s;
  damping (fraction of critical): heave 0.2, roll 0.05, pitch 0.2, surge, sway, yaw 0.1;
  wave: 10 s, ramp 20 s, heave force 2.3e6 N, surge 1e5 N, sway 2e5 N, roll moment 2e6 N m,
  pitch moment 1e8 N m, yaw 1e6 N m: about 0.25 m heave, 2.5° roll, 1° pitch.

Build: `pythonfmu build -f osp/vessel/Vessel6.py` (riser_tools.coupling_loop.build_vessel_fmu)."""
import math

from pythonfmu import Boolean, Fmi2Causality, Fmi2Slave, Fmi2Variability, Real

RHO, G = 1025.0, 9.81
L, B, T, CB, CWP, GMT, GML = 100.0, 20.0, 6.0, 0.70, 0.80, 2.0, 120.0
VOLUME = L * B * T * CB
MASS = RHO * VOLUME
IXX, IYY, IZZ = MASS * (0.35 * B) ** 2, MASS * (0.25 * L) ** 2, MASS * (0.25 * L) ** 2


def _critical(zeta, m, c):
    return 2.0 * zeta * math.sqrt(m * c)


DOFS = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
# name suffixes of the matrices' diagonals: 11 .. 66
IDX = ["11", "22", "33", "44", "55", "66"]
DEFAULTS = {
    "mass": MASS,
    "inertia_xx": IXX, "inertia_yy": IYY, "inertia_zz": IZZ,
    "added_mass_11": 0.05 * MASS, "added_mass_22": 0.8 * MASS, "added_mass_33": 1.0 * MASS,
    "added_mass_44": 0.25 * IXX, "added_mass_55": 1.0 * IYY, "added_mass_66": 0.7 * IZZ,
    "stiffness_11": 3.6e4, "stiffness_22": 3.6e4, "stiffness_33": RHO * G * L * B * CWP,
    "stiffness_44": RHO * G * VOLUME * GMT, "stiffness_55": RHO * G * VOLUME * GML, "stiffness_66": 2.0e7,
}
_M = [MASS] * 3 + [IXX, IYY, IZZ]
_ZETA = [0.1, 0.1, 0.2, 0.05, 0.2, 0.1]
for _i in range(6):
    _m = _M[_i] + DEFAULTS["added_mass_" + IDX[_i]]
    DEFAULTS["damping_" + IDX[_i]] = _critical(_ZETA[_i], _m, DEFAULTS["stiffness_" + IDX[_i]])
DEFAULTS.update({
    "wave_period": 10.0, "ramp": 20.0,
    "wave_force_x": 1e5, "wave_force_y": 2e5, "wave_force_z": 2.3e6,
    "wave_moment_x": 2e6, "wave_moment_y": 1e8, "wave_moment_z": 1e6,
    "wave_phase_x": 0.0, "wave_phase_y": 0.5, "wave_phase_z": 0.0,
    "wave_phase_roll": 1.0, "wave_phase_pitch": -1.5, "wave_phase_yaw": 0.3,
    "max_substep": 0.005,
})
INITIAL = ["initial_" + d for d in DOFS]  # the pose at t = 0 (free decay)
OUT_POSE = DOFS
OUT_VEL = ["surge_velocity", "sway_velocity", "heave_velocity",
           "angular_velocity_x", "angular_velocity_y", "angular_velocity_z"]
# riser's output names: its force on the vessel (global), its moment about the reference point in the
# global frame (top_moment_*) or in the vessel frame (vessel_moment_*: the angular port's torque,
# whose power with p, q, r is M·ω); both moments are applied, connect one of them
INPUTS = ["top_force_x", "top_force_y", "top_force_z", "top_moment_x", "top_moment_y", "top_moment_z",
          "vessel_moment_x", "vessel_moment_y", "vessel_moment_z"]


def rotation(phi, theta, psi):
    """R = Rz(ψ) Ry(θ) Rx(φ) as rows."""
    cf, sf, ct, st, cp, sp = math.cos(phi), math.sin(phi), math.cos(theta), math.sin(theta), math.cos(psi), \
        math.sin(psi)
    return [[cp * ct, cp * st * sf - sp * cf, cp * st * cf + sp * sf],
            [sp * ct, sp * st * sf + cp * cf, sp * st * cf - cp * sf],
            [-st, ct * sf, ct * cf]]


class Vessel6(Fmi2Slave):
    author = "riser"
    description = "a floating vessel in six degrees of freedom fed a riser's force and moment"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        for name, value in DEFAULTS.items():
            setattr(self, name, value)
            self.register_variable(Real(name, causality=Fmi2Causality.parameter,
                                        variability=Fmi2Variability.tunable))
        self.balance_initial_load = True
        self.register_variable(Boolean("balance_initial_load", causality=Fmi2Causality.parameter,
                                       variability=Fmi2Variability.tunable))
        for name in INITIAL:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.parameter,
                                        variability=Fmi2Variability.tunable))
        for name in INPUTS:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.input))
        for name in OUT_POSE + OUT_VEL + ["work", "work_magnitude"]:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.output))
        self._load0 = None
        self._started = False

    # state: pose (6), velocities (6: global translational, vessel-frame angular), the integrals of
    # the angular velocity in the global frame (3) and in the vessel frame (3), for the work
    def _rates(self, t, s, load):
        phi, theta, psi = s[3], s[4], s[5]
        p, q, r = s[9], s[10], s[11]
        R = rotation(phi, theta, psi)
        ramp = self.ramp
        rt = 1.0 if t >= ramp or ramp <= 0 else 0.5 * (1.0 - math.cos(math.pi * t / ramp))
        wt = 2.0 * math.pi * t / self.wave_period
        exc = [a * rt * math.sin(wt + ph) for a, ph in zip(self._wave_amp, self._wave_phase)]
        f, m = load[:3], load[3:6]
        mb = [R[0][i] * m[0] + R[1][i] * m[1] + R[2][i] * m[2] + load[6 + i] for i in range(3)]  # Rᵀ M + M_b
        tau = [f[0], f[1], f[2], mb[0], mb[1], mb[2]]
        acc = [(tau[i] + exc[i] - self._b[i] * s[6 + i] - self._c[i] * s[i]) / self._m[i] for i in range(6)]
        sf, cf, ct = math.sin(phi), math.cos(phi), math.cos(theta)
        qr = q * sf + r * cf
        ang = [p + qr * math.tan(theta), q * cf - r * sf, qr / ct]
        wg = [R[i][0] * p + R[i][1] * q + R[i][2] * r for i in range(3)]
        return s[6:9] + ang + acc + wg + [p, q, r]

    def _start(self):
        self._m = [self.mass] * 3 + [self.inertia_xx, self.inertia_yy, self.inertia_zz]
        self._m = [mi + getattr(self, "added_mass_" + k) for mi, k in zip(self._m, IDX)]
        self._b = [getattr(self, "damping_" + k) for k in IDX]
        self._c = [getattr(self, "stiffness_" + k) for k in IDX]
        self._wave_amp = [self.wave_force_x, self.wave_force_y, self.wave_force_z,
                          self.wave_moment_x, self.wave_moment_y, self.wave_moment_z]
        self._wave_phase = [self.wave_phase_x, self.wave_phase_y, self.wave_phase_z,
                            self.wave_phase_roll, self.wave_phase_pitch, self.wave_phase_yaw]
        if abs(self.initial_pitch) >= 0.5 * math.pi or self.max_substep <= 0 or self.wave_period <= 0:
            raise ValueError("Vessel6: |initial_pitch| < pi/2, max_substep > 0 and wave_period > 0 are required")
        self._state = [getattr(self, n) for n in INITIAL] + [0.0] * 12
        self._started = True

    def exit_initialization_mode(self):
        self._start()
        self._publish()

    def _publish(self):
        for k, name in enumerate(OUT_POSE + OUT_VEL):
            setattr(self, name, self._state[k])

    def do_step(self, t, dt):
        if not self._started:
            self._start()
        load = [getattr(self, n) for n in INPUTS]
        if self._load0 is None:
            self._load0 = list(load) if self.balance_initial_load else [0.0] * 9
        load = [a - b for a, b in zip(load, self._load0)]
        n = max(1, int(math.ceil(dt / self.max_substep - 1e-9)))
        h = dt / n
        s = list(self._state)
        s0 = list(s)
        for k in range(n):
            tk = t + k * h
            k1 = self._rates(tk, s, load)
            k2 = self._rates(tk + h / 2, [a + h / 2 * b for a, b in zip(s, k1)], load)
            k3 = self._rates(tk + h / 2, [a + h / 2 * b for a, b in zip(s, k2)], load)
            k4 = self._rates(tk + h, [a + h * b for a, b in zip(s, k3)], load)
            s = [a + h / 6 * (b1 + 2 * b2 + 2 * b3 + b4) for a, b1, b2, b3, b4 in zip(s, k1, k2, k3, k4)]
        if not all(math.isfinite(x) for x in s) or abs(s[4]) >= 0.5 * math.pi:
            return False  # diverged, or pitched to the z-y-x gimbal lock
        # the riser's whole held force and moment on the vessel's displacement and rotation
        full = [getattr(self, n) for n in INPUTS]
        w = sum(full[i] * (s[i] - s0[i]) + full[3 + i] * (s[12 + i] - s0[12 + i])
                + full[6 + i] * (s[15 + i] - s0[15 + i]) for i in range(3))
        self.work += w
        self.work_magnitude += abs(w)
        self._state = s
        self._publish()
        return True
