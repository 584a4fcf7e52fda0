//! The printer of [`crate::ir`]: one walk over the description, with the few places where
//! GLSL ES 3.00 and WGSL spell things differently chosen by [`Language`].
//!
//! Binary operations keep the tree's grouping exactly (a right operand of equal precedence is
//! parenthesised), so both languages evaluate the same operations in the same order.

use std::fmt::Write as _;

use crate::ir::{BinOp, Expr, Function, Stmt, Ty};

/// A shading language.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Language {
    /// GLSL ES 3.00, for WebGL2 (and, the same text, desktop GLSL from 3.30 on).
    Glsl,
    /// WGSL, for WebGPU.
    Wgsl,
}

impl Language {
    /// Both languages.
    pub const ALL: [Self; 2] = [Self::Glsl, Self::Wgsl];

    /// The usual file extension: `glsl` or `wgsl`.
    #[must_use]
    pub fn extension(self) -> &'static str {
        match self {
            Self::Glsl => "glsl",
            Self::Wgsl => "wgsl",
        }
    }

    pub(crate) fn ty(self, ty: Ty) -> &'static str {
        match (self, ty) {
            (Self::Glsl, Ty::F32) => "float",
            (Self::Glsl, Ty::I32) => "int",
            (Self::Glsl, Ty::Vec3) => "vec3",
            (Self::Glsl, Ty::Vec4) => "vec4",
            (Self::Wgsl, Ty::F32) => "f32",
            (Self::Wgsl, Ty::I32) => "i32",
            (Self::Wgsl, Ty::Vec3) => "vec3<f32>",
            (Self::Wgsl, Ty::Vec4) => "vec4<f32>",
        }
    }
}

/// A float literal that reads back as the same f32 in both languages: the shortest decimal
/// that round-trips (always with a point or an exponent, so never an integer), negative ones
/// parenthesised. WGSL reads a literal as an abstract float first and refuses one beyond
/// f32's range, so where the shortest decimal lies beyond it (`3.4028235e38` for `f32::MAX`)
/// the f32's exact value is written instead.
pub(crate) fn float_literal(v: f32) -> String {
    let mut s = format!("{v:?}");
    if s.parse::<f64>()
        .is_ok_and(|x| x.abs() > f64::from(f32::MAX))
    {
        s = format!("{:?}", f64::from(v));
    }
    if v.is_sign_negative() {
        format!("({s})")
    } else {
        s
    }
}

/// Binding strength of an expression's outermost operation (atoms bind tightest).
fn precedence(e: &Expr) -> u8 {
    match e {
        Expr::Binary(op, ..) => op.precedence(),
        Expr::Neg(_) => 4,
        _ => 5,
    }
}

pub(crate) struct Printer {
    pub(crate) lang: Language,
    pub(crate) out: String,
}

impl Printer {
    pub(crate) fn new(lang: Language) -> Self {
        Self {
            lang,
            out: String::new(),
        }
    }

    fn expr(&self, e: &Expr) -> String {
        let wrap = |child: &Expr, min: u8| {
            let s = self.expr(child);
            if precedence(child) < min {
                format!("({s})")
            } else {
                s
            }
        };
        let list = |args: &[Expr]| {
            args.iter()
                .map(|a| self.expr(a))
                .collect::<Vec<_>>()
                .join(", ")
        };
        match e {
            Expr::Float(v) => float_literal(*v),
            Expr::Int(v) if *v < 0 => format!("({v})"),
            Expr::Int(v) => v.to_string(),
            Expr::Name(n) => n.clone(),
            Expr::Binary(op, l, r) => {
                let p = op.precedence();
                format!("{} {} {}", wrap(l, p), op.symbol(), wrap(r, p + 1))
            }
            Expr::Neg(x) => format!("-{}", wrap(x, 5)),
            Expr::Call(f, args) => {
                let name = match self.lang {
                    Language::Glsl => f.glsl(),
                    Language::Wgsl => f.wgsl(),
                };
                format!("{name}({})", list(args))
            }
            Expr::CallFn(f, args) => format!("{f}({})", list(args)),
            Expr::Swizzle(x, c) => format!("{}.{c}", wrap(x, 5)),
            Expr::Index(x, i) => format!("{}[{}]", wrap(x, 5), self.expr(i)),
            Expr::Construct(ty, args) => format!("{}({})", self.lang.ty(*ty), list(args)),
            Expr::ToFloat(x) => format!("{}({})", self.lang.ty(Ty::F32), self.expr(x)),
            Expr::Select {
                condition,
                if_true,
                if_false,
            } => {
                let (c, t, f) = (
                    self.expr(condition),
                    self.expr(if_true),
                    self.expr(if_false),
                );
                match self.lang {
                    Language::Glsl => format!("({c} ? {t} : {f})"),
                    Language::Wgsl => format!("select({f}, {t}, {c})"),
                }
            }
        }
    }

    fn line(&mut self, depth: usize, text: &str) {
        let _ = writeln!(self.out, "{:1$}{text}", "", 4 * depth);
    }

    fn stmt(&mut self, depth: usize, s: &Stmt) {
        let g = self.lang == Language::Glsl;
        match s {
            Stmt::Let(n, ty, v) | Stmt::Var(n, ty, v) => {
                let (v, ty) = (self.expr(v), self.lang.ty(*ty));
                let text = if g {
                    format!("{ty} {n} = {v};")
                } else {
                    let kw = if matches!(s, Stmt::Let(..)) {
                        "let"
                    } else {
                        "var"
                    };
                    format!("{kw} {n}: {ty} = {v};")
                };
                self.line(depth, &text);
            }
            Stmt::Assign(n, op, v) => {
                let op = op.map_or("", BinOp::symbol);
                let text = format!("{n} {op}= {};", self.expr(v));
                self.line(depth, &text);
            }
            Stmt::For(i, count, body) => {
                let count = self.expr(count);
                let text = if g {
                    format!("for (int {i} = 0; {i} < {count}; {i}++) {{")
                } else {
                    format!("for (var {i}: i32 = 0; {i} < {count}; {i}++) {{")
                };
                self.line(depth, &text);
                for s in body {
                    self.stmt(depth + 1, s);
                }
                self.line(depth, "}");
            }
            Stmt::Return(v) => {
                let text = format!("return {};", self.expr(v));
                self.line(depth, &text);
            }
        }
    }

    pub(crate) fn comment(&mut self, text: &str) {
        for l in text.lines() {
            if l.is_empty() {
                self.line(0, "//");
            } else {
                self.line(0, &format!("// {l}"));
            }
        }
    }

    pub(crate) fn function(&mut self, f: &Function) {
        self.comment(&f.doc);
        let lang = self.lang;
        let params: Vec<String> = f
            .params
            .iter()
            .map(|(n, t)| match lang {
                Language::Glsl => format!("{} {n}", lang.ty(*t)),
                Language::Wgsl => format!("{n}: {}", lang.ty(*t)),
            })
            .collect();
        let header = match lang {
            Language::Glsl => format!("{} {}({}) {{", lang.ty(f.result), f.name, params.join(", ")),
            Language::Wgsl => format!(
                "fn {}({}) -> {} {{",
                f.name,
                params.join(", "),
                lang.ty(f.result)
            ),
        };
        self.line(0, &header);
        for s in &f.body {
            self.stmt(1, s);
        }
        self.line(0, "}");
    }
}

#[cfg(test)]
mod tests {
    use super::float_literal;

    #[test]
    fn literals_read_back_as_the_same_f32_within_its_range() {
        for v in [
            0.1f32,
            1.0,
            -2.5,
            1e-6,
            3.240_625_5,
            f32::MAX,
            -f32::MAX,
            f32::MIN_POSITIVE,
        ] {
            let s = float_literal(v);
            let x: f64 = s
                .trim_matches(|c| c == '(' || c == ')')
                .parse()
                .expect("decimal");
            assert!(x.abs() <= f64::from(f32::MAX), "{s}");
            #[allow(clippy::cast_possible_truncation)]
            let back = x as f32;
            assert_eq!(back, v, "{s}");
            assert!(s.contains(['.', 'e']), "{s} is not an integer literal");
        }
        assert_eq!(float_literal(f32::MAX), "3.4028234663852886e38");
    }
}
