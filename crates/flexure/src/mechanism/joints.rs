//! Joint kinds: each maps its coordinates to the pose of its output frame in
//! its root frame, with derivatives and elastic energy, through one interface.

use crate::energy::{energy_gradient, stiffness};
use crate::joint::Flexure;
use crate::kinematics::{self, Kinematics, Level, Pose};
use nalgebra::{DMatrix, DVector};

/// A joint's pose, first and second derivatives, and elastic energy at its coordinates.
#[derive(Debug, Clone)]
pub struct JointState {
    /// Output frame in the root frame.
    pub pose: Pose,
    /// $3\times k$: rows $(\phi, x, y)$.
    pub jacobian: DMatrix<f64>,
    /// Hessian of $x$ ($k\times k$); that of $\phi$ is zero for every kind here.
    pub hessian_x: DMatrix<f64>,
    /// Hessian of $y$.
    pub hessian_y: DMatrix<f64>,
    /// Elastic energy (J).
    pub energy: f64,
    /// Its gradient.
    pub gradient: DVector<f64>,
    /// Its Hessian.
    pub stiffness: DMatrix<f64>,
    /// A flexure's kinematics buffers, reused by [`Joint::evaluate_into`].
    kinematics: Option<Box<Kinematics>>,
}

/// The interface every joint kind implements.
pub trait Joint {
    /// Number of coordinates.
    fn dof(&self) -> usize;
    /// Coordinates of the unloaded joint.
    fn rest(&self) -> Vec<f64>;
    /// Buffers for [`Joint::evaluate_into`] (the Data of this joint).
    fn state(&self) -> JointState {
        state(self.dof())
    }
    /// Pose, derivatives and energy at `q`, written into `out` (made by
    /// [`Joint::state`]) without allocating.
    fn evaluate_into(&self, q: &[f64], out: &mut JointState);
    /// Pose, derivatives and energy at `q`, in fresh buffers.
    fn evaluate(&self, q: &[f64]) -> JointState {
        let mut s = self.state();
        self.evaluate_into(q, &mut s);
        s
    }
}

/// A pin joint about the root frame's origin, angle $\theta$, with an optional torsional spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Revolute {
    /// N·m/rad (0: free).
    pub stiffness: f64,
    /// Spring's rest angle (rad).
    pub rest: f64,
}

/// A slider along the root frame's x axis, travel $d$, with an optional spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prismatic {
    /// N/m (0: free).
    pub stiffness: f64,
    /// Spring's rest travel (m).
    pub rest: f64,
}

/// A rigid connection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fixed;

fn state(k: usize) -> JointState {
    JointState {
        pose: Pose::default(),
        jacobian: DMatrix::zeros(3, k),
        hessian_x: DMatrix::zeros(k, k),
        hessian_y: DMatrix::zeros(k, k),
        energy: 0.0,
        gradient: DVector::zeros(k),
        stiffness: DMatrix::zeros(k, k),
        kinematics: None,
    }
}

impl Joint for Flexure {
    fn dof(&self) -> usize {
        self.order()
    }
    fn rest(&self) -> Vec<f64> {
        Flexure::rest(self).to_vec()
    }
    fn state(&self) -> JointState {
        let n = self.order();
        let mut s = state(n);
        s.kinematics = Some(Box::new(Kinematics::new(self)));
        for i in 0..n {
            for j in 0..n {
                s.stiffness[(i, j)] = stiffness(self, i, j);
            }
        }
        s
    }
    fn evaluate_into(&self, q: &[f64], s: &mut JointState) {
        let k = s.kinematics.get_or_insert_with(|| Box::new(Kinematics::new(self)));
        kinematics::update(self, q, k, Level::Hessian);
        s.pose = k.pose_root_tip;
        // The update writes every entry of these (same-shaped) buffers:
        // exchanged, not copied, the state's old ones are the next update's.
        std::mem::swap(&mut s.jacobian, &mut k.jacobian_root_tip);
        std::mem::swap(&mut s.hessian_x, &mut k.hessian_root_tip_x);
        std::mem::swap(&mut s.hessian_y, &mut k.hessian_root_tip_y);
        energy_gradient(self, q, s.gradient.as_mut_slice());
        // crate::energy::energy's sum, from the gradient just computed.
        let mut u = 0.0;
        for ((a, k), g) in q.iter().zip(self.rest()).zip(s.gradient.iter()) {
            u += (a - k) * g;
        }
        s.energy = u * 0.5;
    }
}

impl Joint for Revolute {
    fn dof(&self) -> usize {
        1
    }
    fn rest(&self) -> Vec<f64> {
        vec![self.rest]
    }
    fn state(&self) -> JointState {
        let mut s = state(1);
        s.jacobian[(0, 0)] = 1.0;
        s.stiffness[(0, 0)] = self.stiffness;
        s
    }
    fn evaluate_into(&self, q: &[f64], s: &mut JointState) {
        s.pose = Pose { phi: q[0], x: 0.0, y: 0.0 };
        s.energy = 0.5 * self.stiffness * (q[0] - self.rest).powi(2);
        s.gradient[0] = self.stiffness * (q[0] - self.rest);
    }
}

impl Joint for Prismatic {
    fn dof(&self) -> usize {
        1
    }
    fn rest(&self) -> Vec<f64> {
        vec![self.rest]
    }
    fn state(&self) -> JointState {
        let mut s = state(1);
        s.jacobian[(1, 0)] = 1.0;
        s.stiffness[(0, 0)] = self.stiffness;
        s
    }
    fn evaluate_into(&self, q: &[f64], s: &mut JointState) {
        s.pose = Pose { phi: 0.0, x: q[0], y: 0.0 };
        s.energy = 0.5 * self.stiffness * (q[0] - self.rest).powi(2);
        s.gradient[0] = self.stiffness * (q[0] - self.rest);
    }
}

impl Joint for Fixed {
    fn dof(&self) -> usize {
        0
    }
    fn rest(&self) -> Vec<f64> {
        vec![]
    }
    fn evaluate_into(&self, _: &[f64], _: &mut JointState) {}
}

/// One of the joint kinds.
#[derive(Debug, Clone, PartialEq)]
pub enum JointKind {
    /// The Smooth Curvature flexure (boxed: it carries its tables).
    Flexure(Box<Flexure>),
    /// Pin joint.
    Revolute(Revolute),
    /// Slider.
    Prismatic(Prismatic),
    /// Weld of child to parent.
    Fixed(Fixed),
}

impl JointKind {
    /// The kind as its interface.
    pub fn joint(&self) -> &dyn Joint {
        match self {
            JointKind::Flexure(f) => f.as_ref(),
            JointKind::Revolute(r) => r,
            JointKind::Prismatic(p) => p,
            JointKind::Fixed(f) => f,
        }
    }
}
