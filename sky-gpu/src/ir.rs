//! The one description of each shader: typed expressions and statements, written once in Rust
//! and printed as GLSL ES 3.00 and WGSL by [`crate::print`].
//!
//! The language is the small common part of the two: `f32`, `i32`, `vec3` and `vec4` values,
//! arithmetic (scalars and vectors mix as in both languages), the built-in functions both have,
//! `let`/`var` bindings, compound assignment, counted `for` loops and `return`. Choices that
//! would be branches are [`select`]s. Operators build the tree: `a * b + c`.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A value's type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ty {
    /// 32-bit float.
    F32,
    /// 32-bit signed integer.
    I32,
    /// Three floats.
    Vec3,
    /// Four floats.
    Vec4,
}

/// A binary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `<`
    Less,
    /// `>=`
    GreaterEqual,
}

impl BinOp {
    /// The operator's symbol, the same in both languages.
    #[must_use]
    pub fn symbol(self) -> &'static str {
        match self {
            Self::Add => "+",
            Self::Sub => "-",
            Self::Mul => "*",
            Self::Div => "/",
            Self::Less => "<",
            Self::GreaterEqual => ">=",
        }
    }

    /// Binding strength: higher binds tighter.
    #[must_use]
    pub fn precedence(self) -> u8 {
        match self {
            Self::Less | Self::GreaterEqual => 1,
            Self::Add | Self::Sub => 2,
            Self::Mul | Self::Div => 3,
        }
    }
}

/// A built-in function both languages have (under the names [`Builtin::glsl`] and
/// [`Builtin::wgsl`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Builtin {
    /// 2^x, per component.
    Exp2,
    /// √x.
    Sqrt,
    /// 1/√x.
    InverseSqrt,
    /// atan2(y, x).
    Atan2,
    /// The larger of two values, per component.
    Max,
    /// The smaller of two values, per component.
    Min,
    /// `clamp(x, lo, hi)`.
    Clamp,
    /// Dot product.
    Dot,
    /// Cross product of two `vec3`s.
    Cross,
}

impl Builtin {
    /// The GLSL name.
    #[must_use]
    pub fn glsl(self) -> &'static str {
        match self {
            Self::Exp2 => "exp2",
            Self::Sqrt => "sqrt",
            Self::InverseSqrt => "inversesqrt",
            Self::Atan2 => "atan",
            Self::Max => "max",
            Self::Min => "min",
            Self::Clamp => "clamp",
            Self::Dot => "dot",
            Self::Cross => "cross",
        }
    }

    /// The WGSL name.
    #[must_use]
    pub fn wgsl(self) -> &'static str {
        match self {
            Self::InverseSqrt => "inverseSqrt",
            Self::Atan2 => "atan2",
            other => other.glsl(),
        }
    }
}

/// An expression.
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    /// A float literal.
    Float(f32),
    /// An integer literal.
    Int(i32),
    /// A named value: a binding, a parameter or the uniform array.
    Name(String),
    /// A binary operation.
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// Negation.
    Neg(Box<Expr>),
    /// A built-in function call.
    Call(Builtin, Vec<Expr>),
    /// A call of a function of the shader.
    CallFn(String, Vec<Expr>),
    /// A component selection (`.x`, `.xyz`, `.w`).
    Swizzle(Box<Expr>, &'static str),
    /// An array element.
    Index(Box<Expr>, Box<Expr>),
    /// A vector built from components (`vec3(a, b, c)`, or one scalar for all).
    Construct(Ty, Vec<Expr>),
    /// Conversion of an integer to a float.
    ToFloat(Box<Expr>),
    /// `if_true` where `condition` holds, else `if_false` (both evaluated).
    Select {
        /// The condition (a comparison).
        condition: Box<Expr>,
        /// The value where it holds.
        if_true: Box<Expr>,
        /// The value where it does not.
        if_false: Box<Expr>,
    },
}

/// A float literal.
#[must_use]
pub fn float(v: f32) -> Expr {
    Expr::Float(v)
}

/// An integer literal.
#[must_use]
pub fn int(v: i32) -> Expr {
    Expr::Int(v)
}

/// A named value.
#[must_use]
pub fn name(n: &str) -> Expr {
    Expr::Name(n.to_owned())
}

/// A built-in call.
#[must_use]
pub fn call(f: Builtin, args: impl IntoIterator<Item = Expr>) -> Expr {
    Expr::Call(f, args.into_iter().collect())
}

/// A call of one of the shader's own functions.
#[must_use]
pub fn call_fn(f: &str, args: impl IntoIterator<Item = Expr>) -> Expr {
    Expr::CallFn(f.to_owned(), args.into_iter().collect())
}

/// `vec3(x, y, z)`.
#[must_use]
pub fn vec3(x: Expr, y: Expr, z: Expr) -> Expr {
    Expr::Construct(Ty::Vec3, vec![x, y, z])
}

/// A `vec3` with every component `v`.
#[must_use]
pub fn splat3(v: Expr) -> Expr {
    Expr::Construct(Ty::Vec3, vec![v])
}

/// `if_true` where `condition` holds, else `if_false`.
#[must_use]
pub fn select(condition: Expr, if_true: Expr, if_false: Expr) -> Expr {
    Expr::Select {
        condition: Box::new(condition),
        if_true: Box::new(if_true),
        if_false: Box::new(if_false),
    }
}

impl Expr {
    /// Components `components` of a vector (e.g. `"xyz"`).
    #[must_use]
    pub fn swizzle(self, components: &'static str) -> Self {
        Self::Swizzle(Box::new(self), components)
    }

    /// Element `i` of an array.
    #[must_use]
    pub fn at(self, i: Expr) -> Self {
        Self::Index(Box::new(self), Box::new(i))
    }

    /// `self < rhs`.
    #[must_use]
    pub fn less(self, rhs: Expr) -> Self {
        Self::Binary(BinOp::Less, Box::new(self), Box::new(rhs))
    }

    /// `self >= rhs`.
    #[must_use]
    pub fn greater_equal(self, rhs: Expr) -> Self {
        Self::Binary(BinOp::GreaterEqual, Box::new(self), Box::new(rhs))
    }

    /// The integer `self` as a float.
    #[must_use]
    pub fn to_float(self) -> Self {
        Self::ToFloat(Box::new(self))
    }
}

macro_rules! binary {
    ($trait:ident, $method:ident, $op:ident) => {
        impl $trait for Expr {
            type Output = Expr;
            fn $method(self, rhs: Expr) -> Expr {
                Expr::Binary(BinOp::$op, Box::new(self), Box::new(rhs))
            }
        }
        impl $trait<f32> for Expr {
            type Output = Expr;
            fn $method(self, rhs: f32) -> Expr {
                Expr::Binary(BinOp::$op, Box::new(self), Box::new(Expr::Float(rhs)))
            }
        }
        impl $trait<Expr> for f32 {
            type Output = Expr;
            fn $method(self, rhs: Expr) -> Expr {
                Expr::Binary(BinOp::$op, Box::new(Expr::Float(self)), Box::new(rhs))
            }
        }
    };
}
binary!(Add, add, Add);
binary!(Sub, sub, Sub);
binary!(Mul, mul, Mul);
binary!(Div, div, Div);

impl Neg for Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        Expr::Neg(Box::new(self))
    }
}

/// A statement.
#[derive(Debug, Clone, PartialEq)]
pub enum Stmt {
    /// An immutable binding.
    Let(String, Ty, Expr),
    /// A mutable binding.
    Var(String, Ty, Expr),
    /// `name op= value` (`op` `None`: plain assignment).
    Assign(String, Option<BinOp>, Expr),
    /// `for (i = 0; i < count; i++) { body }`, `i` an `i32`.
    For(String, Expr, Vec<Stmt>),
    /// Return a value.
    Return(Expr),
}

/// A function of a shader.
#[derive(Debug, Clone, PartialEq)]
pub struct Function {
    /// Its name.
    pub name: String,
    /// A comment printed above it.
    pub doc: String,
    /// Parameters: name and type.
    pub params: Vec<(String, Ty)>,
    /// The result's type.
    pub result: Ty,
    /// The body.
    pub body: Vec<Stmt>,
}

impl Function {
    /// `vec3 sky_radiance(vec3 dir)` with `body`: every model's entry point.
    #[must_use]
    pub fn sky_radiance(body: Vec<Stmt>) -> Self {
        Self {
            name: "sky_radiance".into(),
            doc: String::new(),
            params: vec![("dir".into(), Ty::Vec3)],
            result: Ty::Vec3,
            body,
        }
    }
}

/// A builder for a function body: bindings return the [`Expr`] that names them.
#[derive(Debug, Default)]
pub struct Body {
    stmts: Vec<Stmt>,
}

impl Body {
    /// A new, empty body.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// `let name: ty = value;`, and the name.
    pub fn let_(&mut self, n: &str, ty: Ty, value: Expr) -> Expr {
        self.stmts.push(Stmt::Let(n.to_owned(), ty, value));
        name(n)
    }

    /// `var name: ty = value;`, and the name.
    pub fn var(&mut self, n: &str, ty: Ty, value: Expr) -> Expr {
        self.stmts.push(Stmt::Var(n.to_owned(), ty, value));
        name(n)
    }

    /// `name = value;`.
    pub fn assign(&mut self, n: &str, value: Expr) {
        self.stmts.push(Stmt::Assign(n.to_owned(), None, value));
    }

    /// `name += value;`.
    pub fn add_assign(&mut self, n: &str, value: Expr) {
        self.stmts
            .push(Stmt::Assign(n.to_owned(), Some(BinOp::Add), value));
    }

    /// A counted loop over `i` in `0..count`, its body built by `f` from the name `i`.
    pub fn for_(&mut self, i: &str, count: Expr, f: impl FnOnce(&mut Body, Expr)) {
        let mut inner = Body::new();
        f(&mut inner, name(i));
        self.stmts.push(Stmt::For(i.to_owned(), count, inner.stmts));
    }

    /// `return value;`.
    pub fn return_(&mut self, value: Expr) {
        self.stmts.push(Stmt::Return(value));
    }

    /// The statements.
    #[must_use]
    pub fn finish(self) -> Vec<Stmt> {
        self.stmts
    }
}
