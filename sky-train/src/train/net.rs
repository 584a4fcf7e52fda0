//! A small fully connected network in f64 for training: inputs → hidden layers with the
//! activation f(x) = 1/(1 + x²) (seed 000 eq. 5) → three linear outputs z. The sky's radiance is
//! ½ z² (eq. 7 through the output activation, see `sky_core::neural`).

/// Layer sizes and a flat parameter vector: per layer, weights (row per output neuron) then
/// biases.
#[derive(Debug, Clone, PartialEq)]
pub struct Net {
    /// Neurons per layer, inputs first, outputs last (e.g. `[6, 12, 3]`).
    pub sizes: Vec<usize>,
    /// All weights and biases, layer by layer.
    pub params: Vec<f64>,
}

/// The activation f(x) = 1/(1 + x²) and its derivative f'(x) = −2x/(1 + x²)².
#[inline]
#[must_use]
pub fn activation(x: f64) -> (f64, f64) {
    let f = 1.0 / (1.0 + x * x);
    (f, -2.0 * x * f * f)
}

/// Scratch space for one forward/backward pass.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    /// Activations per layer (the inputs first).
    act: Vec<Vec<f64>>,
    /// Activation derivatives per hidden layer.
    deriv: Vec<Vec<f64>>,
    /// Back-propagated sensitivities per layer.
    delta: Vec<Vec<f64>>,
}

impl Net {
    /// The number of parameters of a network with these layer sizes.
    #[must_use]
    pub fn param_count(sizes: &[usize]) -> usize {
        sizes.windows(2).map(|w| w[0] * w[1] + w[1]).sum()
    }

    /// A network with parameters drawn by `rng`: weights uniform in ±`scale`/√fan-in, biases
    /// uniform in ±`scale`.
    #[must_use]
    pub fn random(sizes: &[usize], rng: &mut impl rand::Rng, scale: f64) -> Self {
        let mut params = Vec::with_capacity(Self::param_count(sizes));
        for w in sizes.windows(2) {
            #[allow(clippy::cast_precision_loss)]
            let bound = scale / (w[0] as f64).sqrt();
            for _ in 0..w[0] * w[1] {
                params.push(rng.random_range(-bound..=bound));
            }
            for _ in 0..w[1] {
                params.push(rng.random_range(-scale..=scale));
            }
        }
        Self {
            sizes: sizes.to_vec(),
            params,
        }
    }

    /// The outputs z for `input`.
    #[must_use]
    pub fn forward(&self, input: &[f64], scratch: &mut Scratch) -> [f64; 3] {
        forward(&self.sizes, &self.params, input, scratch)
    }

    /// The outputs z for `input` and, in `grads[c]`, the gradient of z_c with respect to every
    /// parameter.
    pub fn jacobian(&self, input: &[f64], s: &mut Scratch, grads: &mut [Vec<f64>; 3]) -> [f64; 3] {
        jacobian(&self.sizes, &self.params, input, s, grads)
    }
}

/// [`Net::forward`] for layer sizes `sizes` and parameters `params` (borrowed, so that trial
/// parameters need no copy).
#[must_use]
pub fn forward(sizes: &[usize], params: &[f64], input: &[f64], s: &mut Scratch) -> [f64; 3] {
    run(sizes, params, input, s);
    let out = &s.act[sizes.len() - 1];
    [out[0], out[1], out[2]]
}

fn run(sizes: &[usize], params: &[f64], input: &[f64], s: &mut Scratch) {
    let layers = sizes.len();
    s.act.resize(layers, Vec::new());
    s.deriv.resize(layers, Vec::new());
    s.delta.resize(layers, Vec::new());
    s.act[0].clear();
    s.act[0].extend_from_slice(input);
    let mut p = 0;
    for l in 1..layers {
        let (n_in, n_out) = (sizes[l - 1], sizes[l]);
        let (w, rest) = params[p..].split_at(n_in * n_out);
        let b = &rest[..n_out];
        p += n_in * n_out + n_out;
        let (prev, cur) = s.act.split_at_mut(l);
        let x = &prev[l - 1];
        let out = &mut cur[0];
        out.clear();
        s.deriv[l].clear();
        let last = l == layers - 1;
        for j in 0..n_out {
            let row = &w[j * n_in..(j + 1) * n_in];
            let h = b[j] + row.iter().zip(x).map(|(a, b)| a * b).sum::<f64>();
            if last {
                out.push(h);
            } else {
                let (f, df) = activation(h);
                out.push(f);
                s.deriv[l].push(df);
            }
        }
    }
}

/// [`Net::jacobian`] for layer sizes `sizes` and parameters `params`.
pub fn jacobian(
    sizes: &[usize],
    params: &[f64],
    input: &[f64],
    s: &mut Scratch,
    grads: &mut [Vec<f64>; 3],
) -> [f64; 3] {
    run(sizes, params, input, s);
    let layers = sizes.len();
    let z = {
        let out = &s.act[layers - 1];
        [out[0], out[1], out[2]]
    };
    for (c, g) in grads.iter_mut().enumerate() {
        g.clear();
        g.resize(params.len(), 0.0);
        // Sensitivity of z_c to the output layer's pre-activations: the unit vector e_c.
        s.delta[layers - 1].clear();
        s.delta[layers - 1].resize(3, 0.0);
        s.delta[layers - 1][c] = 1.0;
        let mut end = params.len();
        for l in (1..layers).rev() {
            let (n_in, n_out) = (sizes[l - 1], sizes[l]);
            let start = end - (n_in * n_out + n_out);
            let (w, _) = params[start..end].split_at(n_in * n_out);
            let (gw, gb) = g[start..end].split_at_mut(n_in * n_out);
            let x = &s.act[l - 1];
            for j in 0..n_out {
                let d = s.delta[l][j];
                if d == 0.0 {
                    continue;
                }
                gb[j] = d;
                for (gwi, xi) in gw[j * n_in..(j + 1) * n_in].iter_mut().zip(x) {
                    *gwi = d * xi;
                }
            }
            if l > 1 {
                let mut prev = std::mem::take(&mut s.delta[l - 1]);
                prev.clear();
                prev.resize(n_in, 0.0);
                for j in 0..n_out {
                    let d = s.delta[l][j];
                    if d == 0.0 {
                        continue;
                    }
                    for (pi, wi) in prev.iter_mut().zip(&w[j * n_in..(j + 1) * n_in]) {
                        *pi += d * wi;
                    }
                }
                for (pi, di) in prev.iter_mut().zip(&s.deriv[l - 1]) {
                    *pi *= di;
                }
                s.delta[l - 1] = prev;
            }
            end = start;
        }
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn jacobian_matches_finite_differences() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        for sizes in [vec![6, 5, 3], vec![6, 4, 3, 3]] {
            let net = Net::random(&sizes, &mut rng, 1.0);
            let input = [0.3, -1.2, 0.5, 0.1, 0.8, 1.1];
            let mut s = Scratch::default();
            let mut grads: [Vec<f64>; 3] = Default::default();
            net.jacobian(&input, &mut s, &mut grads);
            for p in 0..net.params.len() {
                let h = 1e-6;
                let mut plus = net.clone();
                plus.params[p] += h;
                let mut minus = net.clone();
                minus.params[p] -= h;
                let zp = plus.forward(&input, &mut s);
                let zm = minus.forward(&input, &mut s);
                for c in 0..3 {
                    let fd = (zp[c] - zm[c]) / (2.0 * h);
                    assert!(
                        (fd - grads[c][p]).abs() < 1e-6 * (1.0 + fd.abs()),
                        "{sizes:?} param {p} output {c}: {fd} vs {}",
                        grads[c][p]
                    );
                }
            }
        }
    }
}
