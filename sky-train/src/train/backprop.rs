//! Seed 000's training baseline (§III-C, §IV): online backpropagation with momentum, learning
//! rate β = 0.01 and momentum μ = 0.9, minimising eq. 9 on the scaled targets y = 1/(1 + 2L)
//! (the inverse of eq. 7), with the network output y = f(z) = 1/(1 + z²).

use std::time::Instant;

use rand::seq::SliceRandom;

use super::Scaling;
use super::dataset::DataSet;
use super::net::{self, Net, Scratch};

/// Learning rate β.
pub const LEARNING_RATE: f64 = 0.01;
/// Momentum μ.
pub const MOMENTUM: f64 = 0.9;

/// Examples between two looks at the clock.
const BLOCK: usize = 256;

/// One epoch: every example once, in a random order, one update each; cut short when
/// `deadline` passes (checked every `BLOCK` examples: an epoch of a large set or network
/// takes minutes). Returns the number of examples trained on.
pub fn epoch(
    network: &mut Net,
    velocity: &mut [f64],
    set: &DataSet,
    scaling: &Scaling,
    rng: &mut impl rand::Rng,
    deadline: Instant,
) -> usize {
    let mut order: Vec<usize> = (0..set.inputs.len()).collect();
    order.shuffle(rng);
    let mut s = Scratch::default();
    let mut grads: [Vec<f64>; 3] = Default::default();
    let mut step = vec![0.0; network.params.len()];
    for (k, &i) in order.iter().enumerate() {
        if k % BLOCK == 0 && k > 0 && Instant::now() >= deadline {
            return k;
        }
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
    order.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sources::ModelKind;
    use crate::train::dataset::{DataSet, Sampling};
    use rand::SeedableRng;

    /// An epoch whose deadline has passed stops after its first block; one without a deadline
    /// in sight trains on every example.
    #[test]
    fn an_epoch_stops_at_its_deadline() {
        let mut sampling = Sampling::paper(ModelKind::Preetham);
        sampling.turbidities = vec![2.0, 4.0];
        let set = DataSet::training(ModelKind::Preetham, &sampling).expect("valid");
        assert!(set.inputs.len() > 4 * BLOCK, "{}", set.inputs.len());
        let scaling = Scaling::fit(&set);
        let mut rng = rand::rngs::StdRng::seed_from_u64(1);
        let mut net = Net::random(&[6, 12, 3], &mut rng, 0.5);
        let mut velocity = vec![0.0; net.params.len()];
        let past = Instant::now();
        let trained = epoch(&mut net, &mut velocity, &set, &scaling, &mut rng, past);
        assert_eq!(trained, BLOCK);
        let later = Instant::now() + std::time::Duration::from_secs(3600);
        let trained = epoch(&mut net, &mut velocity, &set, &scaling, &mut rng, later);
        assert_eq!(trained, set.inputs.len());
    }
}
