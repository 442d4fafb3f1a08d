//! The buffers of one run, allocated once: nothing is allocated per step.

/// Buffers of one run; nothing is allocated per step.
pub(super) struct Work {
    pub(super) n: usize,
    pub(super) m: usize,
    /// Start of the step: $M$ and $f$ at $(q_0, \dot q_0, t_0)$.
    pub(super) m0: Vec<f64>,
    pub(super) f0: Vec<f64>,
    /// The Newton matrix's data, kept over steps while Newton converges
    /// fast (RADAU5's reuse): $M$, $K_t$, $D_t$, $G$ at the start of the
    /// step where they were last evaluated.
    pub(super) mj: Vec<f64>,
    pub(super) k0: Vec<f64>,
    pub(super) d0: Vec<f64>,
    pub(super) g0: Vec<f64>,
    /// $G$ at the step's start, for the error estimate: the closure forces
    /// $G^T\lambda$ missing from $f$ there lie in its row space, so the
    /// estimate's multipliers absorb them exactly (with a kept $G$ they would
    /// leak, as a growing error in the directions without inertia).
    pub(super) g_start: Vec<f64>,
    /// $W$ ([`System::closure_forces`](crate::dynamics::System::closure_forces))
    /// kept with `g0`, at the step's start with `g_start`, and at a stage.
    pub(super) w0: Vec<f64>,
    pub(super) w_start: Vec<f64>,
    pub(super) forces: Vec<f64>,
    /// Which closure rows hold velocities ([`System::velocity_closures`](crate::dynamics::System::velocity_closures)).
    pub(super) velocity: Vec<bool>,
    /// The closures' violation $c(q_0)$ at the step's start, and whether the
    /// step holds it rather than correct it (an aimed step: module docs of
    /// `newton`).
    pub(super) violation: Vec<f64>,
    pub(super) carry: bool,
    /// The step for which `matrix` and `e` hold their LU factors (NaN: none).
    pub(super) factored: f64,
    /// The last accepted step's unknowns and length (0 before the first):
    /// its collocation polynomial extrapolated gives Newton's start.
    pub(super) prev: Vec<f64>,
    pub(super) prev_h: f64,
    /// The last Newton solve's contraction (0 when one iteration sufficed).
    pub(super) theta: f64,
    /// Scratch for evaluations at the stages.
    pub(super) mass: Vec<f64>,
    pub(super) force: Vec<f64>,
    pub(super) closure: Vec<f64>,
    pub(super) jac: Vec<f64>,
    /// Newton matrix of the stages ($3(n+m)$ square), its pivots, unknowns
    /// $(\ddot Q_1, \ddot Q_2, \ddot Q_3, \Lambda_1, \Lambda_2, \Lambda_3)$, residual.
    pub(super) matrix: Vec<f64>,
    pub(super) pivots: Vec<usize>,
    pub(super) x: Vec<f64>,
    pub(super) r: Vec<f64>,
    /// Stage positions and velocities ($3n$ each).
    pub(super) qs: Vec<f64>,
    pub(super) vs: Vec<f64>,
    /// Error-estimate matrix ($n + m$ square), pivots, right side, and parts.
    pub(super) e: Vec<f64>,
    pub(super) epiv: Vec<usize>,
    pub(super) erhs: Vec<f64>,
    pub(super) rq: Vec<f64>,
    pub(super) rs: Vec<f64>,
    pub(super) eq: Vec<f64>,
    pub(super) ev: Vec<f64>,
    pub(super) qt: Vec<f64>,
    pub(super) vt: Vec<f64>,
    /// Error scales of positions and velocities.
    pub(super) sq: Vec<f64>,
    /// Each coordinate's weight and group (numbered from 0) in the error
    /// test ([`System::error_weights`]), and each group's largest weighted
    /// position and velocity over a step.
    ///
    /// [`System::error_weights`]: crate::dynamics::System::error_weights
    pub(super) weights: Vec<f64>,
    pub(super) groups: Vec<usize>,
    pub(super) group_q: Vec<f64>,
    pub(super) group_v: Vec<f64>,
    pub(super) sv: Vec<f64>,
    /// Newton increments of the stage positions and velocities ($3n$ each).
    pub(super) dq: Vec<f64>,
    pub(super) dv: Vec<f64>,
    /// The previous Newton iteration's increments, for the rounding test.
    pub(super) dq_prev: Vec<f64>,
    pub(super) dv_prev: Vec<f64>,
    /// Whether the Newton matrix takes each stage's own mass matrix
    /// $M(Q_i)$, evaluated with the residual at every iteration, rather
    /// than the kept one: set for the rest of the run when Newton fails
    /// with fresh data (the integrator's module docs say why).
    pub(super) staged: bool,
    /// $M(Q_i)$ of the three stages at the current iterate ($3n^2$), for a staged matrix.
    pub(super) stage_mass: Vec<f64>,
}

impl Work {
    pub(super) fn new(n: usize, m: usize) -> Self {
        let big = 3 * (n + m);
        let z = |k: usize| vec![0.0; k];
        Self {
            n,
            m,
            m0: z(n * n),
            f0: z(n),
            mj: z(n * n),
            factored: f64::NAN,
            prev: z(big),
            prev_h: 0.0,
            theta: 0.0,
            k0: z(n * n),
            d0: z(n * n),
            g0: z(m * n),
            g_start: z(m * n),
            w0: z(m * n),
            w_start: z(m * n),
            forces: z(m * n),
            mass: z(n * n),
            force: z(n),
            closure: z(m),
            jac: z(m * n),
            matrix: z(big * big),
            pivots: vec![0; big],
            x: z(big),
            r: z(big),
            qs: z(3 * n),
            vs: z(3 * n),
            e: z((n + m) * (n + m)),
            epiv: vec![0; n + m],
            erhs: z(n + m),
            rq: z(n),
            rs: z(n),
            eq: z(n),
            ev: z(n),
            qt: z(n),
            vt: z(n),
            sq: z(n),
            weights: vec![1.0; n],
            groups: (0..n).collect(),
            group_q: z(n),
            group_v: z(n),
            sv: z(n),
            dq: z(3 * n),
            dv: z(3 * n),
            dq_prev: z(3 * n),
            dv_prev: z(3 * n),
            velocity: vec![false; m],
            violation: vec![0.0; m],
            carry: false,
            staged: false,
            stage_mass: z(3 * n * n),
        }
    }
}
