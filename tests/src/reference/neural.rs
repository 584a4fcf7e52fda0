//! The neural sky of seed 000 (Satilmis et al., *A Machine Learning Driven Sky Model*) in f64,
//! from the paper's equations: eq. 10 rotates the view so that the sun's azimuth is π; the
//! input V = {√t, θ_sun, v_x, v_y, v_z, |v − s|} is normalised, u = (V − offset) · scale; one
//! hidden layer with f(x) = 1/(1 + x²) (eq. 5); outputs y = f(z) mapped to radiance by
//! scale · ½(1/y − 1) (eq. 7).

/// A 6-H-3 network's parameters, in f64 (the values of a weight file; no sky-core types).
pub struct Network<const H: usize> {
    /// Hidden layer weights, one row of six per neuron.
    pub hidden: [[f64; 6]; H],
    /// Hidden layer biases.
    pub hidden_bias: [f64; H],
    /// Output layer weights, one row per channel.
    pub output: [[f64; H]; 3],
    /// Output layer biases.
    pub output_bias: [f64; 3],
    /// Input normalisation: offsets.
    pub input_offset: [f64; 6],
    /// Input normalisation: scales.
    pub input_scale: [f64; 6],
    /// Output scale per channel.
    pub output_scale: [f64; 3],
}

impl<const H: usize> Network<H> {
    /// Linear RGB radiance for the sun at zenith `theta_s` and azimuth `phi_s` (radians),
    /// turbidity `t` (0 for networks without it), towards the unit vector `view` (+z up,
    /// azimuth from +x towards +y).
    #[must_use]
    pub fn rgb(&self, theta_s: f64, phi_s: f64, t: f64, view: [f64; 3]) -> [f64; 3] {
        // Eq. 10: rotate by −(φ_s − π) about z.
        let r = phi_s - std::f64::consts::PI;
        let v = [
            view[0] * r.cos() + view[1] * r.sin(),
            view[1] * r.cos() - view[0] * r.sin(),
            view[2],
        ];
        let s = [-theta_s.sin(), 0.0, theta_s.cos()]; // the sun at azimuth π
        let d = ((v[0] - s[0]).powi(2) + (v[1] - s[1]).powi(2) + (v[2] - s[2]).powi(2)).sqrt();
        let input = [t.sqrt(), theta_s, v[0], v[1], v[2], d];
        let u: [f64; 6] =
            std::array::from_fn(|k| (input[k] - self.input_offset[k]) * self.input_scale[k]);
        let f = |x: f64| 1.0 / (1.0 + x * x);
        let a: [f64; H] = std::array::from_fn(|j| {
            f(self.hidden_bias[j] + (0..6).map(|k| self.hidden[j][k] * u[k]).sum::<f64>())
        });
        std::array::from_fn(|c| {
            let z = self.output_bias[c] + (0..H).map(|j| self.output[c][j] * a[j]).sum::<f64>();
            self.output_scale[c] * 0.5 * (1.0 / f(z) - 1.0)
        })
    }
}
