//! The knife's work over one step (seed 000 eq. 1, DESIGN §3.2a): the
//! trapezoid of the start and end forces over the increments (dn, |dt|) for
//! a step in which the crack grows, and, without growth, the piecewise
//! integration between the knife positions where the force has a kink or a
//! jump, so that the work matches ΔU + friction to round-off.

use super::equilibrium::Eval;
use super::knife_step::KnifeStep;
use super::simulation::{Model, Workspace};

/// Elastic knife work over `step` by the trapezoid of the start and end
/// equilibria `e0`, `e1`: ½(F_n⁰ + F_n¹)·dn + ½(F_t⁰ + F_t¹)·|dt|, J/m.
pub(super) fn elastic_work(step: &KnifeStep, e0: &Eval, e1: &Eval) -> f64 {
    0.5 * (e0.f_elastic_n() + e1.f_elastic_n()) * step.dn + 0.5 * (e0.f_t + e1.f_t) * step.dt_abs
}

/// Friction work over `step` by the trapezoid of the start and end
/// equilibria `e0`, `e1`, J/m.
pub(super) fn friction_work(step: &KnifeStep, e0: &Eval, e1: &Eval) -> f64 {
    0.5 * (e0.f_fric_n + e1.f_fric_n) * step.dn + 0.5 * (e0.f_fric_t + e1.f_fric_t) * step.dt_abs
}

/// The knife work (elastic, friction) of a step without crack growth,
/// integrated piecewise: trapezoids between the positions where the force
/// may jump, i.e. where a face node passes a kink of the wedge profile
/// (s = 0, the corner, the end of the bevel) while the faces are measured
/// from the edge, and where the edge passes the tip. Between them the force
/// is linear in the knife position up to active-set changes (kinks of U,
/// split by [`segment_work`]), so the work matches ΔU + friction.
///
/// [`Self::up_to_last_break`] integrates from the step's start to its last
/// break before the end; [`Self::close`] adds the last segment once the end
/// equilibrium is known.
#[derive(Debug, Clone, Copy)]
pub(super) struct PiecewiseWork {
    /// Elastic work so far, J/m.
    elastic: f64,
    /// Friction work so far, J/m.
    friction: f64,
    /// Knife advance of the last break, m.
    t: f64,
    /// The equilibrium just past the last break (its right limit).
    start: Eval,
}

impl PiecewiseWork {
    /// The work of `step` (dn > 0, no crack growth) from its start
    /// equilibrium `e0` up to the last break before its end. Allocation-free.
    pub(super) fn up_to_last_break(
        model: &Model,
        ws: &mut Workspace,
        step: &KnifeStep,
        e0: Eval,
    ) -> Self {
        let (mut w_el, mut w_fric) = (0.0, 0.0);
        let mut prev = e0;
        let mut t_prev = 0.0;
        let xi_f = step.xi_finite();
        let eval_mid = |ws: &mut Workspace, t: f64| step.at_advance(model, ws, t);
        let [corner, bevel] = model.profile.kinks();
        let h = model.h;
        loop {
            let y = step.y_edge - t_prev;
            // The next break below y: the grid y_i − c for c ∈ {0, corner,
            // bevel} with y_i = (i+1)·h (rows above the tip), and the tip.
            let mut next = step.y_edge1;
            for c in [0.0, corner, bevel] {
                let k = ((y + c) / h - 1e-9).ceil() - 1.0;
                let yb = k * h - c;
                if yb > next && yb < y && yb > step.y_tip {
                    next = yb;
                }
            }
            if step.y_tip < y && step.y_tip > next {
                next = step.y_tip;
            }
            if next <= step.y_edge1 + 1e-12 * h {
                break;
            }
            // The force jumps at the break: close the segment with its
            // left limit and open the next with the right limit.
            let t = step.y_edge - next;
            let eps = 1e-9 * h;
            let before = eval_mid(ws, t - eps);
            let after = eval_mid(ws, t + eps);
            let (we, wf) = segment_work(ws, &eval_mid, t_prev, &prev, t, &before, xi_f, 8);
            w_el += we;
            w_fric += wf;
            prev = after;
            t_prev = t;
        }
        Self {
            elastic: w_el,
            friction: w_fric,
            t: t_prev,
            start: prev,
        }
    }

    /// The step's whole work (elastic, friction), J/m: the last segment, from
    /// the last break to the end equilibrium `e1`, added. Leaves `ws` with
    /// `e1`'s gaps, reactions and strip forces (re-evaluated if the segment
    /// was split inside). Allocation-free.
    pub(super) fn close(
        self,
        model: &Model,
        ws: &mut Workspace,
        step: &KnifeStep,
        e1: &Eval,
    ) -> (f64, f64) {
        let (mut w_el, mut w_fric) = (self.elastic, self.friction);
        let eval_mid = |ws: &mut Workspace, t: f64| step.at_advance(model, ws, t);
        // segment_work evaluates inside the segment only if the contact
        // sets differ at its ends; then restore the end state's buffers
        // (the surface deflection reads them).
        let evaluated_inside = self.start.contacts != e1.contacts;
        let (we, wf) = segment_work(
            ws,
            &eval_mid,
            self.t,
            &self.start,
            step.dn,
            e1,
            step.xi_finite(),
            8,
        );
        w_el += we;
        w_fric += wf;
        if evaluated_inside {
            let again = step.at_extension(model, ws, 0.0);
            debug_assert_eq!(again.energy.to_bits(), e1.energy.to_bits());
        }
        (w_el, w_fric)
    }
}

/// Knife work (elastic, friction) over knife advances t_a → t_b of a step
/// without crack growth (tangential advance ξ per unit vertical), from the
/// end states `ea`, `eb`. The forces are linear in t while the contact active
/// sets stay the same; where they change the force has a kink (continuous,
/// the energy being C¹). A segment whose ends differ in active sets is split
/// at the kink found from the two one-sided slopes (two extra evaluations);
/// if the sets on either side of it still differ from the ends' (several
/// changes), or the lines do not cross inside, the halves are split again,
/// up to `depth` times, then integrated by the trapezoid.
#[allow(clippy::too_many_arguments)]
fn segment_work(
    ws: &mut Workspace,
    eval_at: &impl Fn(&mut Workspace, f64) -> Eval,
    t_a: f64,
    ea: &Eval,
    t_b: f64,
    eb: &Eval,
    xi: f64,
    depth: u32,
) -> (f64, f64) {
    let power = |e: &Eval| e.f_elastic_n() + xi * e.f_t;
    let friction = |e: &Eval| e.f_fric_n + xi * e.f_fric_t;
    let len = t_b - t_a;
    let trapezoid = (
        0.5 * (power(ea) + power(eb)) * len,
        0.5 * (friction(ea) + friction(eb)) * len,
    );
    if ea.contacts == eb.contacts || len <= 0.0 || depth == 0 {
        return trapezoid;
    }
    let eps = 1e-4 * len;
    let (ea2, eb2) = (eval_at(ws, t_a + eps), eval_at(ws, t_b - eps));
    let ka = (power(&ea2) - power(ea)) / eps;
    let kb = (power(eb) - power(&eb2)) / eps;
    // Intersection of the two lines: power(ea) + ka (t − t_a) = power(eb) + kb (t − t_b).
    let ts = (power(eb) - power(ea) - kb * t_b + ka * t_a) / (ka - kb);
    let single = ts > t_a + eps && ts < t_b - eps && {
        let (l, r) = (eval_at(ws, ts - eps), eval_at(ws, ts + eps));
        l.contacts == ea.contacts && r.contacts == eb.contacts
    };
    if single {
        let part = |q: &dyn Fn(&Eval) -> f64| {
            let left = q(ea) + (q(&ea2) - q(ea)) / eps * (ts - t_a);
            let right = q(eb) + (q(eb) - q(&eb2)) / eps * (ts - t_b);
            0.5 * (q(ea) + left) * (ts - t_a) + 0.5 * (right + q(eb)) * (t_b - ts)
        };
        return (part(&power), part(&friction));
    }
    let tm = if ts > t_a + eps && ts < t_b - eps {
        ts
    } else {
        0.5 * (t_a + t_b)
    };
    let em = eval_at(ws, tm);
    let (w1, f1) = segment_work(ws, eval_at, t_a, ea, tm, &em, xi, depth - 1);
    let (w2, f2) = segment_work(ws, eval_at, tm, &em, t_b, eb, xi, depth - 1);
    (w1 + w2, f1 + f2)
}
