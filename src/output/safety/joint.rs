//! A reduced contact's resultants in one state, for the safety tables:
//! normal force, summed shear, closed area, the pairs' states.

use crate::contact::law::ContactState;
use crate::results::{state_counts, ContactRun, Run};

/// A reduced contact's resultants in one state: normal force N
/// (compression positive), the magnitude T of its summed shear force, its
/// closed area and its pairs' states.
pub(super) struct Joint {
    pub(super) normal: f64,
    pub(super) shear: f64,
    pub(super) area: f64,
    pub(super) states: [usize; 3],
}

impl Joint {
    pub(super) fn of(run: &Run, c: &ContactRun, contact: usize) -> Joint {
        let (mut normal, mut shear, mut area, mut states) = (0.0, [0.0; 3], 0.0, Vec::new());
        for (p, _) in run.model.pairs.iter().enumerate().filter(|(_, q)| q.contact == contact) {
            states.push(c.states[p]);
            if c.states[p] == ContactState::Open {
                continue;
            }
            normal -= c.pairs[p].sigma_n * c.areas[p];
            let t = c.shear(p);
            (0..3).for_each(|i| shear[i] += t[i] * c.areas[p]);
            area += c.areas[p];
        }
        Joint { normal, shear: shear.iter().map(|x| x * x).sum::<f64>().sqrt(), area, states: state_counts(&states) }
    }

    /// `(c A + N f) / T` with the scene's c and f (infinite without shear).
    pub(super) fn factor(&self, cohesion: f64, friction: f64) -> f64 {
        (cohesion * self.area + self.normal.max(0.0) * friction) / self.shear
    }
}
