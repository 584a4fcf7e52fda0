//! Seed 000's training baseline (§III-C, §IV): online backpropagation with momentum, learning
//! rate β = 0.01 and momentum μ = 0.9, minimising eq. 9 on the scaled targets y = 1/(1 + 2L)
//! (the inverse of eq. 7), with the network output y = f(z) = 1/(1 + z²).

use rand::seq::SliceRandom;

use super::Scaling;
use super::dataset::DataSet;
use super::net::{self, Net, Scratch};

/// Learning rate β.
pub const LEARNING_RATE: f64 = 0.01;
/// Momentum μ.
pub const MOMENTUM: f64 = 0.9;

/// One epoch: every example once, in a random order, one update each.
pub fn epoch(
    network: &mut Net,
    velocity: &mut [f64],
    set: &DataSet,
    scaling: &Scaling,
    rng: &mut impl rand::Rng,
) {
    let mut order: Vec<usize> = (0..set.inputs.len()).collect();
    order.shuffle(rng);
    let mut s = Scratch::default();
    let mut grads: [Vec<f64>; 3] = Default::default();
    let mut step = vec![0.0; network.params.len()];
    for i in order {
        let u = scaling.apply(&set.inputs[i]);
        let z = net::jacobian(&network.sizes, &network.params, &u, &mut s, &mut grads);
        step.iter_mut().for_each(|g| *g = 0.0);
        for c in 0..3 {
            let target = 1.0 / (1.0 + 2.0 * set.targets[i][c] / scaling.output_scale);
            let (y, dy) = net::activation(z[c]);
            // d/dp (y − y_t)² = 2 (y − y_t) f'(z) dz/dp.
            let factor = 2.0 * (y - target) * dy;
            for (st, g) in step.iter_mut().zip(&grads[c]) {
                *st += factor * g;
            }
        }
        for ((p, v), g) in network
            .params
            .iter_mut()
            .zip(velocity.iter_mut())
            .zip(&step)
        {
            *v = MOMENTUM * *v - LEARNING_RATE * g;
            *p += *v;
        }
    }
}
