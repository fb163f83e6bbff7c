"""A floating body's heave as an FMI 2.0 Co-Simulation FMU (pythonfmu), to couple riser to in
libcosim: (M + A) x'' + C x' + K x = F_wave r(t) sin(2πt/T) + (force − force(0)), the riser's
force at the start taken as balanced by the body's buoyancy; r(t) = ½(1 − cos(πt/ramp)) grows the
wave. Out: heave, heave_velocity (and the work of the riser's force on the body, its value at t_n
times the body's displacement over each step, and the sum of its magnitudes). In: force (riser's
top_force_z), force_mean (riser's top_force_z_mean, used with force_hold 4 and 5). RK4 at steps
of at most 5 ms inside each communication step.

How the riser's force is held over a step (issue 29, the buoy; docs/theory.md §7.3,
riser_tools.coupling_exchange): `force_hold` 1 holds the force of t_n (the default), 2 and 3 the
Adams–Bashforth extrapolations (3F_n − F_{n−1})/2 and (23F_n − 16F_{n−1} + 5F_{n−2})/12, 4 the
input `force_mean` (riser's top_force_z_mean: its mean force over the step that ended at t_n), 5
the same with AB2 over successive means, (3M_n − M_{n−1})/2;
`line_mass` m̂ > 0 (default 0) integrates with mass + m̂ and holds the force plus m̂ times the
body's acceleration at t_n (the line's inertia at the hang-off made implicit in the body: the
added-mass partitioned exchange); `force_cutoff` f_c > 0 (Hz, default 0) holds instead the force
low-passed at the communication points by `force_filter_order` (default 2) first-order stages,
y_n = α y_{n−1} + (1 − α) u_n, α = exp(−2π f_c h).

Build: `pythonfmu build -f osp/vessel/Vessel.py` (riser_tools.coupling_loop.build_vessel_fmu).
Defaults: the 2000 t vessel of docs/theory.md §7.3 (M + A = 3000 t, K = 5.03 MN/m, 5 % damping,
a 10 s wave of 1.1 MN)."""
import math

from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Integer, Real


class Vessel(Fmi2Slave):
    author = "riser"
    description = "heave of a floating body fed a riser's top force"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.mass = 3.0e6
        self.damping = 3.883e5
        self.stiffness = 5.0276e6
        self.wave_force = 1.1e6
        self.wave_period = 10.0
        self.ramp = 20.0
        self.force = 0.0
        self.force_mean = 0.0
        self.heave = 0.0
        self.heave_velocity = 0.0
        self.work = 0.0
        self.work_magnitude = 0.0
        self.line_mass = 0.0
        self.force_hold = 1
        self.force_cutoff = 0.0
        self.force_filter_order = 2
        self._filtered = None  # the low-passed held force, one value per stage
        self._force0 = None
        self._past = []  # the forces of t_{n−1}, t_{n−2} (relative to the start's)
        self._past_mean = None  # riser's step mean of the step before
        self._acceleration = 0.0  # the body's acceleration at the end of its last step
        for name in ["mass", "damping", "stiffness", "wave_force", "wave_period", "ramp", "line_mass", "force_cutoff"]:
            self.register_variable(Real(name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.tunable))
        for name in ["force_hold", "force_filter_order"]:
            self.register_variable(Integer(name, causality=Fmi2Causality.parameter,
                                           variability=Fmi2Variability.tunable))
        self.register_variable(Real("force", causality=Fmi2Causality.input))
        self.register_variable(Real("force_mean", causality=Fmi2Causality.input))
        for name in ["heave", "heave_velocity", "work", "work_magnitude"]:
            self.register_variable(Real(name, causality=Fmi2Causality.output))

    def _rates(self, t, x, v, force):
        r = 0.5 * (1.0 - math.cos(math.pi * min(t, self.ramp) / self.ramp))
        f = self.wave_force * r * math.sin(2 * math.pi * t / self.wave_period) + force
        return v, (f - self.damping * v - self.stiffness * x) / (self.mass + self.line_mass)

    def do_step(self, t, dt):
        if self._force0 is None:
            self._force0 = self.force
        now = self.force - self._force0
        hist = [now] + self._past
        mode = int(self.force_hold)
        if mode <= 3:
            weights = {1: [1.0], 2: [1.5, -0.5], 3: [23 / 12, -16 / 12, 5 / 12]}[mode]
            # the first steps hold what the history allows
            weights = weights if len(hist) >= len(weights) else {1: [1.0], 2: [1.5, -0.5]}[len(hist)]
            force = sum(w * f for w, f in zip(weights, hist))
        else:
            # riser's mean over the step that ended at t_n (top_force_z_mean), held (4), or with
            # AB2 over successive means for their lag of h (5)
            mean = self.force_mean - self._force0
            prev = mean if self._past_mean is None else self._past_mean
            force = mean if mode == 4 else 1.5 * mean - 0.5 * prev
            self._past_mean = mean
        force += self.line_mass * self._acceleration
        self._past = hist[:2]
        if self.force_cutoff > 0.0:
            alpha = math.exp(-2.0 * math.pi * self.force_cutoff * dt)
            if self._filtered is None:
                self._filtered = [force] * max(1, int(self.force_filter_order))
            for i in range(len(self._filtered)):
                self._filtered[i] = alpha * self._filtered[i] + (1.0 - alpha) * force
                force = self._filtered[i]
        n = max(1, int(math.ceil(dt / 0.005)))
        h = dt / n
        x, v = self.heave, self.heave_velocity
        for k in range(n):
            tk = t + k * h
            a1, b1 = self._rates(tk, x, v, force)
            a2, b2 = self._rates(tk + h / 2, x + h / 2 * a1, v + h / 2 * b1, force)
            a3, b3 = self._rates(tk + h / 2, x + h / 2 * a2, v + h / 2 * b2, force)
            a4, b4 = self._rates(tk + h, x + h * a3, v + h * b3, force)
            x += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4)
            v += h / 6 * (b1 + 2 * b2 + 2 * b3 + b4)
        # the riser's whole force (held over the step) on the body's displacement
        self.work += self.force * (x - self.heave)
        self.work_magnitude += abs(self.force * (x - self.heave))
        self.heave, self.heave_velocity = x, v
        self._acceleration = self._rates(t + dt, x, v, force)[1]
        return True
