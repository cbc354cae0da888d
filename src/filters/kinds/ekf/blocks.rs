//! The state and covariance in blocks of four lanes (`Blocks`, `Cov`), and the products
//! the filter's equations need of them, in the lane type the CPU's widest copy takes
//! (`crate::isa`).

use super::*;

/// A vector in the state's block layout `[q (4), ω (3), δ (3)]`, each block one SIMD
/// value of four lanes (the three-long blocks with a fourth lane that stays zero).
///
/// Stored as `wide::f64x4`; an update works on any [`Lanes`] type (`V`), 256-bit AVX
/// registers where the CPU has them (`crate::isa::widest_lanes`), loaded at its start and
/// stored at its end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Blocks<V = f64x4> {
    pub(super) q: V,
    pub(super) w: V,
    pub(super) d: V,
}

/// `[f(0), f(1), …]`. Where there is an AVX copy (`crate::isa::HAS_AVX_COPY`), a loop
/// that is always inlined: `core::array::from_fn` may stay out of line, and an
/// out-of-line call from the AVX copy runs baseline code, where the lanes' operations are
/// calls too. Everywhere else `core::array::from_fn`, where the loop costs more
/// instructions (docs/PERFORMANCE.md).
#[inline(always)]
pub(super) fn array<T: Copy, const N: usize>(mut f: impl FnMut(usize) -> T) -> [T; N] {
    if !crate::isa::HAS_AVX_COPY {
        return core::array::from_fn(f);
    }
    let mut out = [f(0); N];
    for (i, o) in out.iter_mut().enumerate().skip(1) {
        *o = f(i);
    }
    out
}

/// A three-vector in four lanes, the fourth zero.
#[inline(always)]
pub(super) fn lanes3<V: Lanes>(t: V::Token, x: f64, y: f64, z: f64) -> V {
    V::new(t, [x, y, z, 0.0])
}

/// Lane `i` of `v`.
#[inline(always)]
pub(super) fn lane<V: Lanes>(v: V, i: usize) -> f64 {
    v.to_array()[i]
}

/// The dot product of two quaternion blocks, summed as `((a0 b0 + a1 b1) + a2 b2) + a3 b3`.
#[inline(always)]
pub(super) fn dot4<V: Lanes>(a: V, b: V) -> f64 {
    let p = (a * b).to_array();
    ((p[0] + p[1]) + p[2]) + p[3]
}

impl<V: Lanes> Blocks<V> {
    #[inline(always)]
    pub(super) fn load(b: &Blocks, t: V::Token) -> Blocks<V> {
        Blocks { q: V::load(t, b.q), w: V::load(t, b.w), d: V::load(t, b.d) }
    }

    #[inline(always)]
    pub(super) fn store(&self) -> Blocks {
        Blocks { q: self.q.store(), w: self.w.store(), d: self.d.store() }
    }

    #[inline(always)]
    pub(super) fn plus(&self, o: &Blocks<V>) -> Blocks<V> {
        Blocks { q: self.q + o.q, w: self.w + o.w, d: self.d + o.d }
    }

    #[inline(always)]
    pub(super) fn minus(&self, o: &Blocks<V>) -> Blocks<V> {
        Blocks { q: self.q - o.q, w: self.w - o.w, d: self.d - o.d }
    }

    #[inline(always)]
    pub(super) fn scaled(&self, a: f64) -> Blocks<V> {
        let a = V::splat(self.q.token(), a);
        Blocks { q: self.q * a, w: self.w * a, d: self.d * a }
    }

    pub(super) fn is_finite(&self) -> bool {
        all_finite([&self.q, &self.w, &self.d])
    }
}

impl Blocks {
    /// The state's ten values in order [q, ω, δ], for reading and writing in place.
    pub(super) fn values_mut(&mut self) -> impl Iterator<Item = &mut f64> {
        let Blocks { q, w, d } = self;
        q.as_array_mut()
            .iter_mut()
            .chain(w.as_array_mut()[..3].iter_mut())
            .chain(d.as_array_mut()[..3].iter_mut())
    }
}

/// A block of P with `C` columns of four lanes: the q rows, or the ω or δ rows with a
/// fourth lane that stays zero.
pub(super) type Cols<const C: usize, V = f64x4> = [V; C];

/// The symmetric 10×10 state covariance P, kept as the six blocks of its upper
/// triangle (the lower ones are their transposes). The model couples q with ω (through
/// the exponential map) and ω with δ (through the gyroscope), and each measurement reads
/// a few states, so every product below is written per block: dense 10×10 algebra spent
/// most of its instructions multiplying zeros (docs/PERFORMANCE.md).
///
/// Each block is stored by columns, a column one SIMD value (the `wide` crate's
/// `f64x4`), so that a product is a sum of column multiples and the rank-one
/// corrections a few vector operations per column. Explicit because this crate's build
/// turns LLVM's SLP vectoriser off (`.cargo/config.toml`): it slowed the small filters'
/// dependent chains (docs/PERFORMANCE.md).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Cov<V = f64x4> {
    pub(super) qq: Cols<4, V>,
    pub(super) qw: Cols<3, V>,
    pub(super) qd: Cols<3, V>,
    pub(super) ww: Cols<3, V>,
    pub(super) wd: Cols<3, V>,
    pub(super) dd: Cols<3, V>,
}

/// `e_j s`: lane `j` set to `s`, the others zero.
#[inline(always)]
pub(super) fn unit<V: Lanes>(t: V::Token, j: usize, s: f64) -> V {
    let mut v = [0.0; 4];
    v[j] = s;
    V::new(t, v)
}

/// `s I` as three padded columns.
#[inline(always)]
pub(super) fn diag3<V: Lanes>(t: V::Token, s: f64) -> Cols<3, V> {
    array(
        #[inline(always)]
        |j| unit(t, j, s),
    )
}

/// The columns of a 4-row nalgebra matrix.
#[inline(always)]
pub(super) fn cols<V: Lanes, const C: usize>(t: V::Token, m: &SMatrix<f64, 4, C>) -> Cols<C, V> {
    let s = m.as_slice();
    array(
        #[inline(always)]
        |j| V::new(t, [s[4 * j], s[4 * j + 1], s[4 * j + 2], s[4 * j + 3]]),
    )
}

/// The lanes of every column, for reading single entries: `[column][row]`.
#[inline(always)]
pub(super) fn entries<V: Lanes, const C: usize>(c: &Cols<C, V>) -> [[f64; 4]; C] {
    c.map(|v| v.to_array())
}

/// The entries of stored columns, read where they are: `[column][row]`.
#[inline(always)]
pub(super) fn in_place<const C: usize>(c: &Cols<C>) -> [&[f64; 4]; C] {
    array(
        #[inline(always)]
        |j| c[j].as_array_ref(),
    )
}

/// `A B` for `A` given by its columns (4×K) and `B` (K×C) by its entries `b(k, j)`:
/// column `j` is `Σ_k a_k b(k, j)`, summed in k order (nalgebra's order).
#[inline(always)]
pub(super) fn mul_cols<V: Lanes, const K: usize, const C: usize>(
    a: &Cols<K, V>,
    b: impl Fn(usize, usize) -> f64,
) -> Cols<C, V> {
    let t = a[0].token();
    array(
        #[inline(always)]
        |j| {
            let mut acc = a[0] * V::splat(t, b(0, j));
            for (k, ak) in a.iter().enumerate().skip(1) {
                acc += *ak * V::splat(t, b(k, j));
            }
            acc
        },
    )
}

/// Column-wise `x + y`.
#[inline(always)]
pub(super) fn add_cols<V: Lanes, const C: usize>(x: Cols<C, V>, y: Cols<C, V>) -> Cols<C, V> {
    array(
        #[inline(always)]
        |j| x[j] + y[j],
    )
}

/// `M ← M − Σ_k u_k w_kᵀ`: entry `(i, j)` is `m_ij − ((u_0,i w_0,j + u_1,i w_1,j) +
/// u_2,i w_2,j)`, so with `u = w` entries `(i, j)` and `(j, i)` come out the same.
#[inline(always)]
pub(super) fn sub_rank3<V: Lanes, const C: usize>(m: &mut Cols<C, V>, u: [V; 3], w: [V; 3]) {
    let tk = u[0].token();
    let w = w.map(|c| c.to_array());
    for (j, col) in m.iter_mut().enumerate() {
        let t = u[0] * V::splat(tk, w[0][j]) + u[1] * V::splat(tk, w[1][j]);
        *col -= t + u[2] * V::splat(tk, w[2][j]);
    }
}

/// `M ← M − u wᵀ` for a block off P's diagonal (stored once, so no twin entry has to
/// come out the same): the heading correction's restricted-gain terms.
#[inline(always)]
pub(super) fn sub_outer<V: Lanes, const C: usize>(m: &mut Cols<C, V>, u: V, w: V) {
    let w = w.to_array();
    for (j, col) in m.iter_mut().enumerate() {
        *col -= u * V::splat(u.token(), w[j]);
    }
}

/// True when every lane of every column is finite and their sum does not overflow: an
/// infinite or NaN lane makes its lane's sum infinite or NaN, and `x · 0` is zero only
/// for a finite `x`. (The zero fourth lanes of the three-row blocks stay finite unless a
/// real entry is not.) A sum that overflows from finite lanes, near 1e308, also answers
/// false: such a covariance is refused like a non-finite one.
#[inline(always)]
pub(super) fn all_finite<'a, V: Lanes + 'a>(cols: impl IntoIterator<Item = &'a V>) -> bool {
    let mut cols = cols.into_iter();
    let Some(first) = cols.next() else { return true };
    let acc = cols.fold(*first, |acc, c| acc + *c);
    (acc * V::splat(first.token(), 0.0)).to_array() == [0.0; 4]
}

impl Cov {
    pub(super) fn diagonal(q: f64, w: f64, d: f64) -> Cov {
        let zero = [f64x4::splat(0.0); 3];
        Cov {
            qq: array(
                #[inline(always)]
                |j| unit((), j, q),
            ),
            qw: zero,
            qd: zero,
            ww: diag3((), w),
            wd: zero,
            dd: diag3((), d),
        }
    }

    /// The stored value behind entry (r, c) of the full matrix, state order
    /// [q0..q3, ω, δ]. An entry of a lower off-diagonal block is its upper twin.
    pub(super) fn entry_mut(&mut self, r: usize, c: usize) -> &mut f64 {
        let block = |i: usize| match i {
            0..=3 => (0, i),
            4..=6 => (1, i - 4),
            _ => (2, i - 7),
        };
        let ((br, ir), (bc, ic)) = (block(r), block(c));
        let (column, row) = match (br, bc) {
            (0, 0) => (&mut self.qq[ic], ir),
            (0, 1) => (&mut self.qw[ic], ir),
            (1, 0) => (&mut self.qw[ir], ic),
            (0, 2) => (&mut self.qd[ic], ir),
            (2, 0) => (&mut self.qd[ir], ic),
            (1, 1) => (&mut self.ww[ic], ir),
            (1, 2) => (&mut self.wd[ic], ir),
            (2, 1) => (&mut self.wd[ir], ic),
            _ => (&mut self.dd[ic], ir),
        };
        &mut column.as_array_mut()[row]
    }
}

impl<V: Lanes> Cov<V> {
    /// Stores every column into `to` where it lies: a `Cov` built whole and then assigned
    /// was assembled on the stack and copied into place with `memcpy` (608 bytes; 142
    /// instructions per update, callgrind, baseline ISA).
    #[inline(always)]
    pub(super) fn store_into(&self, to: &mut Cov) {
        #[inline(always)]
        fn each<V: Lanes, const C: usize>(from: &Cols<C, V>, to: &mut Cols<C>) {
            for (t, f) in to.iter_mut().zip(from) {
                *t = f.store();
            }
        }
        each(&self.qq, &mut to.qq);
        each(&self.qw, &mut to.qw);
        each(&self.qd, &mut to.qd);
        each(&self.ww, &mut to.ww);
        each(&self.wd, &mut to.wd);
        each(&self.dd, &mut to.dd);
    }

    /// `P hᵀ` for a measurement row that reads q only, through `hq`.
    #[inline(always)]
    pub(super) fn times_q(&self, hq: V) -> Blocks<V> {
        let t = hq.token();
        let h = hq.to_array();
        let q = mul_cols::<V, 4, 1>(&self.qq, |k, _| h[k])[0];
        // `array`, not `map`: LLVM left `map`'s loop out of line in the heading update.
        let w: [f64; 3] = array(
            #[inline(always)]
            |j| dot4(self.qw[j], hq),
        );
        let d: [f64; 3] = array(
            #[inline(always)]
            |j| dot4(self.qd[j], hq),
        );
        Blocks { q, w: lanes3(t, w[0], w[1], w[2]), d: lanes3(t, d[0], d[1], d[2]) }
    }

    /// Column `4 + i` of P (the ω_i column).
    #[inline(always)]
    pub(super) fn column_w(&self, i: usize) -> Blocks<V> {
        let wd = entries(&self.wd);
        Blocks { q: self.qw[i], w: self.ww[i], d: lanes3(self.ww[0].token(), wd[0][i], wd[1][i], wd[2][i]) }
    }

    /// Column `7 + i` of P (the δ_i column).
    #[inline(always)]
    pub(super) fn column_d(&self, i: usize) -> Blocks<V> {
        Blocks { q: self.qd[i], w: self.wd[i], d: self.dd[i] }
    }

    /// `P ← P − Σ_k v_k v_kᵀ`.
    #[inline(always)]
    pub(super) fn subtract_rank3(&mut self, v: &[Blocks<V>; 3]) {
        let (q, w, d) = (v.map(|b| b.q), v.map(|b| b.w), v.map(|b| b.d));
        // Of seven orders tried this one left the fewest instructions (register
        // allocation; docs/PERFORMANCE.md). Every entry's bits are the same in any order.
        sub_rank3(&mut self.qq, q, q);
        sub_rank3(&mut self.qd, q, d);
        sub_rank3(&mut self.qw, q, w);
        sub_rank3(&mut self.ww, w, w);
        sub_rank3(&mut self.wd, w, d);
        sub_rank3(&mut self.dd, d, d);
    }

    pub(super) fn is_finite(&self) -> bool {
        all_finite(
            self.qq.iter().chain(&self.qw).chain(&self.qd).chain(&self.ww).chain(&self.wd).chain(&self.dd),
        )
    }
}

/// Three Kalman corrections at once: rows `h_k` with `u_k = P h_kᵀ` (all from the same
/// P), the innovation covariance `S = H P Hᵀ + R` (3×3, read from its upper triangle)
/// and the innovations `ν`. With `S = L Lᵀ` (Cholesky) and `V = U L⁻ᵀ`, the posterior
/// is `x + V L⁻¹ν` and `P − V Vᵀ`: the batch update, which equals three scalar
/// corrections in turn (sequential processing, R diagonal) with one pass over P
/// instead of three. Each entry of `V Vᵀ` is `Σ_k v_k,i v_k,j` summed in k order, so P
/// stays exactly symmetric. `None` when S is not positive definite and finite.
#[inline(always)]
pub(super) fn absorb3<V: Lanes>(
    x: &mut Blocks<V>,
    p: &mut Cov<V>,
    u: &[Blocks<V>; 3],
    s: [[f64; 3]; 3],
    nu: [f64; 3],
) -> Option<()> {
    let l00 = s[0][0].sqrt();
    let (l10, l20) = (s[0][1] / l00, s[0][2] / l00);
    let d1 = s[1][1] - l10 * l10;
    let l11 = d1.sqrt();
    let l21 = (s[1][2] - l20 * l10) / l11;
    let d2 = s[2][2] - l20 * l20 - l21 * l21;
    let l22 = d2.sqrt();
    let finite = l00.is_finite() && l10.is_finite() && l20.is_finite() && l21.is_finite() && l22.is_finite();
    if !(s[0][0] > 0.0 && d1 > 0.0 && d2 > 0.0 && finite) {
        return None;
    }
    // V Lᵀ = U column by column, and y = L⁻¹ν.
    let (r0, r1, r2) = (1.0 / l00, 1.0 / l11, 1.0 / l22);
    let v0 = u[0].scaled(r0);
    let v1 = u[1].minus(&v0.scaled(l10)).scaled(r1);
    let v2 = u[2].minus(&v0.scaled(l20)).minus(&v1.scaled(l21)).scaled(r2);
    let y0 = nu[0] * r0;
    let y1 = (nu[1] - l10 * y0) * r1;
    let y2 = (nu[2] - l20 * y0 - l21 * y1) * r2;
    *x = x.plus(&v0.scaled(y0)).plus(&v1.scaled(y1)).plus(&v2.scaled(y2));
    p.subtract_rank3(&[v0, v1, v2]);
    Some(())
}
