"""The distribution of X over a higher-order sample space (section 8, eq. 41 and its
generalisations): pmf, moments, modes and the class decomposition (figure 11).

``P(X = k) = W(k) / sum_j W(j)`` with ``W(k) = Phi_{N,p}(k) Q*(k)`` (see
:mod:`symhx.spaces._classes`): ``Phi`` is the simple-space weight of eq. (8) and ``Q*(k)`` a short
sum of N-independent integers ``U_e(k)`` times ``p**e`` (or 1 for the ``;distinct`` weighting).

Arithmetic (same contract as :mod:`symhx.distribution`):

* exact ``Fraction`` results for int / Fraction / sympy Rational ``p`` (binary splitting of the
  normaliser and moments; ``N <= 10**5``);
* otherwise mpmath at ``dps`` digits (plus ``10 + 2 log10 N`` guard digits): for
  ``N <= 20000`` every ``W(k)`` by a product recurrence; above, a float64 screen keeps only the
  ``k`` whose weight is within ``dps`` + guard digits of the largest.
* modes are decided exactly for every rational ``p`` (floats and mpf included, at their exact
  binary value): the argmax of a float64 ``log W`` (absolute error < 1e-8 for ``N <= 10**6``) is
  only a seed; :func:`symhx.certify.space_candidates` keeps every ``k`` that Arb balls cannot
  prove to weigh less than it, and those candidates are compared exactly (integers) or by
  interval arithmetic with an exact fall-back, so ties are found exactly.
* for a sympy irrational ``p`` the same scan and comparisons run on a rigorous Arb ball of
  ``p`` itself (:func:`symhx.certify.real_ball`), the precision doubled until every comparison
  is proved; a true tie (no precision separates two weights) raises
  :class:`~symhx.certify.UndecidedError`: pass ``p`` as an exact rational to have it decided.

Threads: the mpmath path computes in the calling thread's context (:mod:`symhx._mpctx`); the
cached weights and moments are stored exported (global mpf), so one frozen distribution may be
used by many threads at once.
"""

from __future__ import annotations

import math
from fractions import Fraction
from functools import cached_property
from typing import Any

import mpmath
import numpy as np

from symhx._mpctx import export, local, mp
from symhx._numeric import (
    G_mp,
    digits_of,
    mp_value,
)
from symhx.certify import (
    UndecidedError,
    arb_prec,
    bits_for,
    certified_sign,
    decide_with_rising_precision,
    rational_bracket,
    real_ball,
    space_candidates,
    space_candidates_ball,
    space_q_ball,
    to_arb,
)
from symhx.distribution import (
    Distribution,
    SimpleDistribution,
    binary_split,
    simple_modes,
)
from symhx.spaces._classes import (
    Space,
    check_space_work,
    paper_label,
    parse_space,
    shape_excess,
)
from symhx.validation import (
    DEFAULT_DPS,
    DEFAULT_SPACE,
    InputError,
    check_dps,
    check_N,
    check_p,
    exact_work_refusal,
    show_exact,
)

__all__ = [
    "ClassDecomposition",
    "SpaceDistribution",
    "class_decomposition",
    "class_probabilities",
    "distribution",
    "modes",
]

#: below this N the mpmath path computes every W(k) (no float screen); also the documented work
#: limit of :func:`class_decomposition` on the mpmath path, which lists every ``P(X = k, class)``
#: (``N * classes`` mpf values: N = 20000 over eq41 takes ~3 s)
DIRECT_LIMIT = 20_000
#: exact integer comparisons are attempted up to this many bits
EXACT_BITS_LIMIT = 8_000_000


# --------------------------------------------------------------------------- float64 screen
_LOGU: dict[str, np.ndarray] = {}


def log_U_table(space: Space, K: int) -> np.ndarray:
    """float64 ``log U_e(k)`` for ``e = 0..m`` (rows) and ``k = 1..K`` (columns); ``-inf`` for 0.

    Computed as sums of logs of positive terms (no cancellation): relative error ~1e-15.
    """
    key = space.name
    got = _LOGU.get(key)
    if got is not None and got.shape[1] >= K:
        return got[:, :K]
    K2 = max(K, 2 * got.shape[1]) if got is not None else K
    m = space.max_excess
    out = np.full((m + 1, K2), -np.inf)
    mp_ = min(space.max_parts, K2)
    for k in range(1, mp_ + 1):
        for e, u in enumerate(space.U(k)):
            if u > 0:
                out[e, k - 1] = math.log(u)
    if K2 > mp_:
        ks = np.arange(mp_ + 1, K2 + 1, dtype=float)
        rmax = max((r for pairs in space.coefficients for r, _ in pairs), default=0)
        logfall = [np.zeros_like(ks)]
        for i in range(rmax):
            logfall.append(logfall[-1] + np.log(ks - i))
        logrise = np.zeros_like(ks)
        for e, pairs in enumerate(space.coefficients):
            if e:
                logrise = logrise + np.log(ks + (e - 1))
            if not pairs:
                continue
            terms = np.array([math.log(c) + logfall[r] for r, c in pairs])
            top = terms.max(axis=0)
            inner = top + np.log(np.exp(terms - top).sum(axis=0))
            out[e, mp_:] = logrise + inner
    _LOGU[key] = out
    return out[:, :K]


def _logp_float(fr: Fraction) -> float:
    return math.log(fr.numerator) - math.log(fr.denominator)


def _logp_float_of(p: Any, fr: Fraction | None) -> float:
    """float64 ``log p`` (a seed or a screen, never a decision): exact ``fr``, or a sympy
    irrational from its rigorous Arb ball."""
    if fr is not None:
        return _logp_float(fr)
    with arb_prec(128):
        ball = real_ball(p)
        lo_hi = rational_bracket(ball) if ball > 0 else None
    if lo_hi is None:
        raise InputError(f"p={p} cannot be enclosed at 128 bits (is it positive and finite?)")
    return _logp_float(lo_hi[0])


def log_Q_float(space: Space, K: int, logp: float) -> np.ndarray:
    """float64 ``log Q*(k)``, ``k = 1..K``."""
    lu = log_U_table(space, K)
    if space.weighting == "length":
        lu = lu + (np.arange(space.max_excess + 1) * logp)[:, None]
    top = lu.max(axis=0)
    return top + np.log(np.exp(lu - top).sum(axis=0)) - math.log(space.denominator)


def log_W_float(space: Space, N: int, logp: float) -> np.ndarray:
    """float64 ``log W(k)`` for ``k = 1..N`` (absolute error < 1e-8 for ``N <= 10**6``)."""
    from scipy.special import gammaln

    ks = np.arange(1, N + 1, dtype=float)
    lphi = ks * logp + (gammaln(N + 1.0) - gammaln(N - ks + 1.0)) - np.log(ks)
    return lphi + log_Q_float(space, N, logp)


# --------------------------------------------------------------------------- exact comparisons
def _rational(p: Any, fr: Fraction | None) -> Fraction:
    """The exact value of ``p`` (``fr`` if known); a sympy irrational has none: ValueError
    (callers that can work with an irrational use its Arb ball instead)."""
    if fr is None:
        fr, p = check_p(p)
    if fr is None:
        raise InputError(f"p={p} is irrational: an exact weight needs a rational p (pass an "
                         f"int, Fraction, decimal string, float or mpf)")
    return fr


def compare_weights(space: Space, N: int, fr: Fraction, j: int, k: int) -> int:
    """Sign of ``W(k) - W(j)`` (certified; exact integers on a near tie)."""
    if j == k:
        return 0
    if j > k:
        return -compare_weights(space, N, fr, k, j)
    a, b = fr.numerator, fr.denominator
    d = k - j
    Qk, Qj = space.Qnum(k, a, b), space.Qnum(j, a, b)

    def exact() -> int:
        bits = d * (N.bit_length() + max(a.bit_length(), b.bit_length()) + 1)
        if bits > EXACT_BITS_LIMIT:
            raise UndecidedError(f"W({k}) vs W({j}) for N={N}: exact comparison needs ~{bits} "
                                 f"bits")
        lhs = a**d * math.perm(N - j, d) * j * Qk
        rhs = b**d * k * Qj
        return (lhs > rhs) - (lhs < rhs)

    if d <= 64 or N < 2000:
        return exact()

    def ball() -> Any:
        return (d * (to_arb(a).log() - to_arb(b).log())
                + to_arb(N - j + 1).lgamma() - to_arb(N - k + 1).lgamma()
                + to_arb(j).log() - to_arb(k).log()
                + to_arb(Qk).log() - to_arb(Qj).log())

    start = bits_for(N, a.bit_length() + b.bit_length() + 2 * k.bit_length() + 64)
    return certified_sign(ball, start_bits=start, max_bits=16 * start, exact_fn=exact)


def space_modes(space: Space, N: int, p: Any, fr: Fraction | None = None) -> tuple[int, ...]:
    """All maximisers of ``P(X = k)`` over ``space``: exact for rational ``p``; for a sympy
    irrational proved on Arb balls of ``p``."""
    N = check_N(N, minimum=1)
    if fr is None:
        fr, p = check_p(p)
    if N == 1:
        return (1,)
    check_space_work(space, N, "modes")
    if fr is None:
        return _irrational_modes(space, N, p)
    lw = log_W_float(space, N, _logp_float(fr))  # float64 seed: decides nothing
    cand = space_candidates(space, N, fr, int(np.argmax(lw)) + 1)  # Arb-certified superset
    best = [cand[0]]
    for k in cand[1:]:
        s = compare_weights(space, N, fr, best[0], k)
        if s > 0:
            best = [k]
        elif s == 0:
            best.append(k)
    return tuple(sorted(best))


def _log_weight_ratio_ball(space: Space, N: int, pa: Any, j: int, k: int) -> Any:
    """Ball of ``log W(k) - log W(j)`` for ``p`` in the ball ``pa`` (``j < k``):
    ``(k-j) log p + lgamma(N-j+1) - lgamma(N-k+1) + log j - log k + log Q*(k) - log Q*(j)``."""
    return ((k - j) * pa.log() + to_arb(N - j + 1).lgamma() - to_arb(N - k + 1).lgamma()
            + to_arb(j).log() - to_arb(k).log()
            + space_q_ball(space, k, pa).log() - space_q_ball(space, j, pa).log())


def _irrational_modes(space: Space, N: int, p: Any) -> tuple[int, ...]:
    """The modes at an irrational ``p``, proved on Arb balls of ``p`` itself: the candidate scan
    of :func:`symhx.certify.space_candidates_ball` and the pairwise signs of
    ``log W(k) - log W(j)`` are evaluated with ``p`` a ball, the precision doubled until one
    candidate is proved heavier than every other. Several candidates that no precision up to
    ``MAX_IRRATIONAL_BITS`` separates (a true tie) raise :class:`UndecidedError`."""
    top = int(np.argmax(log_W_float(space, N, _logp_float_of(p, None)))) + 1  # a seed only
    last: list[int] = []

    def attempt(bits: int) -> tuple[int, ...] | None:
        with arb_prec(bits):
            pa = real_ball(p)
            bracket = rational_bracket(pa) if pa > 0 else None
            if bracket is None:
                return None
            cand = space_candidates_ball(space, N, pa, bracket[1], top)
            signs: dict[tuple[int, int], Any] = {}

            def heavier(o: int, k: int) -> bool:  # proved: W(o) > W(k)
                j, kk = min(o, k), max(o, k)
                if (j, kk) not in signs:  # the ball of log W(kk) - log W(j)
                    signs[j, kk] = _log_weight_ratio_ball(space, N, pa, j, kk)
                d = signs[j, kk]
                return bool(d > 0) if o == kk else bool(d < 0)

            alive = [k for k in cand if not any(heavier(o, k) for o in cand if o != k)]
        last[:] = alive
        return (alive[0],) if len(alive) == 1 else None

    start = 96 + 2 * N.bit_length() + 64
    return decide_with_rising_precision(
        attempt, start_bits=start,
        undecided=lambda bits: (
            f"the modes of X at the irrational p={str(p)[:60]} (N={N}, {space.name}) are not "
            f"decided at {bits} bits: W(k) for k in {tuple(last)} agree (a true tie, or p "
            f"within 2**-{bits} of one); pass p as an exact rational (e.g. a Fraction or "
            f"sympy Rational) to have the tie decided exactly"))


# --------------------------------------------------------------------------- the distribution
class SpaceDistribution(Distribution):
    """X over a higher-order sample space. Build it with :func:`distribution`.

    Attributes as :class:`symhx.distribution.Distribution`; ``space`` is the canonical name and
    :attr:`sample_space` the parsed :class:`~symhx.spaces.Space`.
    """

    def __init__(self, N: int, p: Any, space: Space, *, dps: int | None = DEFAULT_DPS) -> None:
        if not isinstance(space, Space):
            raise TypeError(f"space must be a parsed symhx.spaces.Space (use parse_space), got "
                            f"{type(space).__name__} {space!r}")
        self._setup(N, p, dps)
        check_space_work(space, self.N, "a distribution")
        self.sample_space = space
        self.space = space.name

    def _check_exact_work(self, what: str, limit: int, name: str) -> None:
        """Refuse (before any work) exact sums whose integers would be too large: the simple
        space's measure with ``p``'s bits counted ``m + 1`` times (``Q*`` carries ``b**m``)."""
        assert self.fr is not None
        bits_p = self.fr.numerator.bit_length() + self.fr.denominator.bit_length()
        work = self.N * (self.N.bit_length() + (self.sample_space.max_excess + 1) * bits_p)
        if work > limit:
            raise exact_work_refusal(
                f"{what} in exact rational arithmetic over space {self.space!r} would need "
                f"~{work:.2g} bit-terms for N={show_exact(self.N)}, p={show_exact(self.fr)} "
                f"(documented work limit {limit}, symhx.distribution.{name})")

    # ----------------------------------------------------------------- exact path
    @cached_property
    def _exact_moments(self) -> tuple[Fraction, Fraction, Fraction]:
        from symhx.distribution import EXACT_WORK_LIMIT

        self._check_exact_work("summing the distribution", EXACT_WORK_LIMIT, "EXACT_WORK_LIMIT")
        assert self.fr is not None
        sp, N = self.sample_space, self.N
        a, b = self.fr.numerator, self.fr.denominator
        den = sp.Qden(b)
        g = binary_split(N, a, b, lambda j: (sp.Qnum(j, a, b), j)) / den
        m1 = binary_split(N, a, b, lambda j: (sp.Qnum(j, a, b), 1)) / den
        m2 = binary_split(N, a, b, lambda j: (j * sp.Qnum(j, a, b), 1)) / den
        return g, m1, m2

    def _exact_partial(self, k: int) -> Fraction:
        from symhx.distribution import EXACT_WORK_LIMIT

        self._check_exact_work("summing the distribution", EXACT_WORK_LIMIT, "EXACT_WORK_LIMIT")
        assert self.fr is not None
        sp = self.sample_space
        a, b = self.fr.numerator, self.fr.denominator
        return binary_split(self.N, a, b, lambda j: (sp.Qnum(j, a, b), j), k) / sp.Qden(b)

    def weight_exact(self, k: int) -> Fraction:
        """``W(k) = Phi_{N,p}(k) Q*(k)`` exactly (needs rational ``p``)."""
        fr = _rational(self.p, self.fr)
        if not 1 <= k <= self.N:
            return Fraction(0)
        return fr**k * Fraction(math.perm(self.N, k), k) * self.sample_space.Qstar(k, fr)

    # ----------------------------------------------------------------- mpmath path
    # Computed in the calling thread's context (symhx._mpctx); what is cached on the object or
    # handed to the base class (_terms, _mp_moments, _mp_terms, results) is exported.
    def _logp(self) -> float:
        return _logp_float_of(self.p, self.fr)

    def _runs(self) -> list[tuple[int, int]]:
        N = self.N
        if N <= DIRECT_LIMIT:
            return [(1, N)]
        lw = log_W_float(self.sample_space, N, self._logp())
        cut = lw.max() - self._wdps * math.log(10) - 20
        idx = np.nonzero(lw >= cut)[0] + 1
        runs: list[tuple[int, int]] = []
        lo = prev = int(idx[0])
        for k in idx[1:]:
            k = int(k)
            if k != prev + 1:
                runs.append((lo, prev))
                lo = k
            prev = k
        runs.append((lo, prev))
        return runs

    def _q_mp(self, k: int, pe: list[mpmath.mpf]) -> mpmath.mpf:
        U = self.sample_space.U(k)
        if self.sample_space.weighting == "distinct":
            return pe[0] * sum(U)
        total = pe[0] * U[0]
        for e in range(1, len(U)):
            if U[e]:
                total += pe[e] * U[e]
        return total

    def _pe(self, pm: mpmath.mpf) -> list[mpmath.mpf]:
        ctx = mp()
        D = self.sample_space.denominator
        if self.sample_space.weighting == "distinct":
            return [ctx.mpf(1) / D]
        pe = [ctx.mpf(1) / D]
        for _ in range(self.sample_space.max_excess):
            pe.append(pe[-1] * pm)
        return pe

    def _log_phi_mp(self, k: int, pm: mpmath.mpf) -> mpmath.mpf:
        ctx = mp()
        N = self.N
        return (k * ctx.log(pm) + k * ctx.log(N) + G_mp(N, k - 1) - ctx.log(k))

    def _p_mp(self) -> mpmath.mpf:
        """``p`` in this thread's context at the working precision (set by the caller)."""
        return mp_value(self.p, self.fr)

    @cached_property
    def _terms(self) -> dict[int, mpmath.mpf]:
        """``{k: W(k)}`` (exported mpf at dps + guard) for every significant k."""
        N = self.N
        out: dict[int, mpmath.mpf] = {}
        ctx = mp()
        with ctx.workdps(self._wdps):
            pm = self._p_mp()
            pe = self._pe(pm)
            sp = self.sample_space
            runs = self._runs()
            # Q*(k) in fixed point: integers pe_int[e] ~ 2**P p**e / D. All terms are positive
            # and Q*(k) >= 1 (U_0 = D), so the relative error is below (m+1) max(U) 2**-P;
            # U_e(k) grows with k beyond max_parts, hence the max over small k and kmax.
            kmax = max(hi for _, hi in runs)
            small = range(1, min(kmax, sp.max_parts) + 1)
            extra = max(u.bit_length() for k in (*small, kmax) for u in sp.U(k))
            P = mpmath.libmp.dps_to_prec(self._wdps) + extra + 20
            pe_int = [int(ctx.floor(x * ctx.mpf(2) ** P)) for x in pe]
            scale = ctx.mpf(2) ** -P
            distinct = sp.weighting == "distinct"
            for lo, hi in runs:
                t = N * pm if lo == 1 else ctx.exp(self._log_phi_mp(lo, pm))
                for k in range(lo, hi + 1):
                    U = sp.U(k)
                    if distinct:
                        q = pe_int[0] * sum(U)
                    else:
                        q = 0
                        for a_, u in zip(pe_int, U, strict=True):
                            q += a_ * u
                    out[k] = export(t * q * scale)
                    t = t * pm * ((N - k) * k) / (k + 1)
        return out

    @cached_property
    def _mp_norm(self) -> mpmath.mpf:
        """``sum_k W(k)`` at ``dps`` + guard digits (exported)."""
        terms = local(self._terms)  # this thread's values: operators round in its context
        ctx = mp()
        with ctx.workdps(self._wdps):
            return export(ctx.fsum(terms.values()))

    @cached_property
    def _mp_moments(self) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
        """``(log normaliser, mean, variance)`` at dps + guard digits (the meaning of every
        space; exported)."""
        terms = local(self._terms)
        ctx = mp()
        s0 = local(self._mp_norm)
        with ctx.workdps(self._wdps):
            mu = ctx.fsum(k * w for k, w in terms.items()) / s0
            var = ctx.fsum((k - mu) ** 2 * w for k, w in terms.items()) / s0
            return export((ctx.log(s0), mu, var))

    def _float_logw(self) -> tuple[np.ndarray, float]:
        return log_W_float(self.sample_space, self.N, self._logp()), 0.0

    def _mp_weight(self, k: int) -> mpmath.mpf:
        """``W(k)`` in this thread's context at the working precision (set by the caller)."""
        w = self._terms.get(k)
        if w is not None:
            return local(w)
        pm = self._p_mp()
        return mp().exp(self._log_phi_mp(k, pm)) * self._q_mp(k, self._pe(pm))

    def _mp_terms(self, lo: int, hi: int) -> list[tuple[int, mpmath.mpf]]:
        """``[(k, P(X = k))]`` at dps + guard digits (exported, for the base class)."""
        if self.N <= DIRECT_LIMIT:  # every W(k) is in _terms
            ks: Any = range(lo, hi + 1)
        else:  # float screen relative to the largest weight in [lo, hi]
            lw = self._float_lw[lo - 1:hi]
            cut = lw.max() - self._wdps * math.log(10) - 20
            ks = [lo + int(i) for i in np.nonzero(lw >= cut)[0]]
        ctx = mp()
        s0 = local(self._mp_norm)
        with ctx.workdps(self._wdps):
            return [(k, export(self._mp_weight(k) / s0)) for k in ks]

    @cached_property
    def _float_lw(self) -> np.ndarray:
        return log_W_float(self.sample_space, self.N, self._logp())

    # ----------------------------------------------------------------- per-k values
    def _pmf1(self, k: int) -> Any:
        if self.exact:
            return self.weight_exact(k) / self._exact_moments[0]
        ctx = mp()
        s0 = local(self._mp_norm)
        with ctx.workdps(self._wdps):
            return export(self._mp_weight(k) / s0, self.dps)

    def _logpmf1(self, k: int) -> mpmath.mpf:
        if self.exact:
            return self._log_fraction(self._pmf1(k))
        ctx = mp()
        s0 = local(self._mp_norm)
        with ctx.workdps(self._wdps):
            w = self._terms.get(k)
            if w is not None:
                return export(ctx.log(w) - ctx.log(s0), self.dps)
            pm = self._p_mp()
            lw = self._log_phi_mp(k, pm) + ctx.log(self._q_mp(k, self._pe(pm)))
            return export(lw - ctx.log(s0), self.dps)

    @property
    def normaliser(self) -> Any:
        """``sum_k W(k)``: the generalisation of ``Gamma_{N,p}`` (eq. 8) to this space."""
        if self.dps is None:
            return self._float_exp(self.log_normaliser)
        if self.exact:
            return self._exact_moments[0]
        return export(self._mp_norm, self.dps)

    @property
    def log_normaliser(self) -> Any:
        """``log`` of :attr:`normaliser`."""
        if self.dps is None:
            return float(self._ftab["lognorm"])
        if self.exact:
            return self._log_fraction(self._exact_moments[0])
        return export(self._mp_moments[0], self.dps)

    def modes(self) -> tuple[int, ...]:
        """All maximisers of ``P(X = k)`` (exact for rational ``p``; proved on Arb balls for
        an irrational ``p``)."""
        return space_modes(self.sample_space, self.N, self.p, self.fr)

    def table(self) -> list[tuple[int, Any]]:
        """``[(k, P(X = k)) for k in 1..N]`` (zeros for k outside the significant range;
        refused above the row limits of :meth:`symhx.distribution.SimpleDistribution.table`)."""
        self._check_table()
        if self.dps is None:
            return [(k, float(v)) for k, v in enumerate(self._ftab["pmf"], 1)]
        if self.exact:
            g = self._exact_moments[0]
            return [(k, self.weight_exact(k) / g) for k in range(1, self.N + 1)]
        terms = self._terms
        ctx = mp()
        s0 = local(self._mp_norm)
        with ctx.workdps(self._wdps):
            vals = [(k, local(terms[k]) / s0 if k in terms else ctx.mpf(0))
                    for k in range(1, self.N + 1)]
        return [(k, export(v, self.dps)) for k, v in vals]


def distribution(N: int, p: Any, *, space: str | Space = DEFAULT_SPACE,
                 dps: int | None = DEFAULT_DPS, weighting: str | None = None) -> Distribution:
    """The distribution of X over a sample space (see :func:`symhx.spaces.parse_space`).

    Parameters
    ----------
    N : int
        Number of vertices (``N = n + 1`` for ``n`` pipes).
    p : int, Fraction, sympy Rational, float or mpf
        Impact probability ``> 0``; exact types give Fraction results.
    space : str
        ``"simple"``, ``"eq41"``, ``"eq41-printed"``, ``"excess<=m"``, optionally with
        ``";distinct"``.
    dps : int or None
        Significant digits of mpmath results; ``None`` for float64.
    weighting : {"length", "distinct"}, optional
        Alternative to the ``;distinct`` suffix.

    Returns
    -------
    Distribution
        :class:`symhx.distribution.SimpleDistribution` for the simple space (length weighting
        and distinct weighting coincide there), else :class:`SpaceDistribution`.

    >>> d = distribution(3, Fraction(1, 2), space="excess<=1")
    >>> d.pmf(1), d.mean()
    (Fraction(36, 73), Fraction(123, 73))
    """
    sp = parse_space(space, weighting)
    if sp.base == "simple":
        return SimpleDistribution(N, p, dps=dps)
    return SpaceDistribution(N, p, sp, dps=dps)


def modes(N: int, p: Any, *, space: str | Space = DEFAULT_SPACE, weighting: str | None = None
          ) -> tuple[int, ...]:
    """All maximisers of ``P(X = k)`` over ``space``, increasing (exact for rational ``p``).

    >>> modes(100, Fraction(1, 50), space="eq41"), modes(100, Fraction(1, 50), space="simple")
    ((53,), (49,))
    """
    sp = parse_space(space, weighting)
    N = check_N(N, minimum=1)
    fr, p = check_p(p)
    if sp.base == "simple":
        return simple_modes(N, fr, p)
    return space_modes(sp, N, p, fr)


# --------------------------------------------------------------------------- classes
class ClassDecomposition:
    """``P(X = k, class = s)`` for every class ``s`` of a space (figure 11).

    Attributes
    ----------
    shapes : tuple
        The classes, e.g. ``((), (2,), (3,), (2, 2), (4,))`` for eq. (41).
    labels : dict
        class -> the paper's name (``"phi^{1,0}"``).
    joint : dict
        class -> list of ``P(X = k, class)`` for ``k = 1..N``.
    totals : dict
        class -> ``P(class)``.
    by_excess : dict
        excess -> total probability of the classes with that excess.
    """

    def __init__(self, dist: SpaceDistribution | Any, shapes: tuple[tuple[int, ...], ...],
                 joint: dict[tuple[int, ...], list[Any]], totals: dict[tuple[int, ...], Any]
                 ) -> None:
        self.distribution = dist
        self.shapes = shapes
        self.labels = {s: paper_label(s) for s in shapes}
        self.joint = joint
        self.totals = totals
        groups: dict[int, list[Any]] = {}
        for s in shapes:
            groups.setdefault(shape_excess(s), []).append(totals[s])
        by: dict[int, Any] = {}
        dps = getattr(dist, "dps", None)
        for e, vals in groups.items():
            if all(isinstance(v, Fraction) for v in vals):
                by[e] = sum(vals, Fraction(0))
            else:  # mpf: add at dps + 10 digits in this thread's context, round to dps
                ctx = mp()
                with ctx.workdps((dps or 15) + 10):
                    tot = ctx.fsum(vals)
                by[e] = export(tot, dps or 15)
        self.by_excess = by

    def __repr__(self) -> str:
        return f"ClassDecomposition({self.distribution!r}, classes={len(self.shapes)})"


def class_decomposition(N: int, p: Any, *, space: str | Space = "eq41", dps: int = DEFAULT_DPS,
                        weighting: str | None = None) -> ClassDecomposition:
    """Split ``P(X = k)`` by class (the paper's figure 11): exact for rational ``p``.

    ``P(X = k, s) = Phi_{N,p}(k) w_e R*_s(k) / sum_j W(j)``; the classes add up to the pmf.

    Raises
    ------
    ValueError
        On the mpmath path (``p`` a float, mpf or irrational) ``N > DIRECT_LIMIT`` (20000, a
        documented work limit: every ``k`` is listed); in exact arithmetic the limits of
        :func:`distribution` (``EXACT_N_LIMIT``, ``EXACT_WORK_LIMIT``, ``MAX_SPACE_WORK``).

    >>> cd = class_decomposition(4, Fraction(1, 2), space="eq41")
    >>> sum(cd.totals.values()), cd.totals[(4,)]
    (Fraction(1, 1), Fraction(8, 75))
    """
    sp = parse_space(space, weighting)
    dps = check_dps(dps)
    dist = distribution(N, p, space=sp, dps=dps)
    N = dist.N
    joint: dict[tuple[int, ...], list[Any]] = {}
    totals: dict[tuple[int, ...], Any] = {}
    if dist.exact:
        assert dist.fr is not None
        fr = Fraction(dist.fr)
        g = dist.normaliser
        for s in sp.shapes:
            we = fr ** shape_excess(s) if sp.weighting == "length" else Fraction(1)
            row = [fr**k * Fraction(math.perm(N, k), k) * we * sp.ratio(s, k) / g
                   for k in range(1, N + 1)]
            joint[s] = row
            totals[s] = sum(row, Fraction(0))
        return ClassDecomposition(dist, sp.shapes, joint, totals)
    if N > DIRECT_LIMIT:
        raise InputError(f"class_decomposition on the mpmath path lists every k: N="
                         f"{show_exact(N)} is beyond the documented work limit N <= "
                         f"{DIRECT_LIMIT} (symhx.spaces._dist.DIRECT_LIMIT); exact rational p "
                         f"lists every k in Fractions, or raise that constant")
    guard = 10 + 2 * digits_of(N)
    ctx = mp()
    with ctx.workdps(dps + guard):
        pm = mp_value(dist.p, dist.fr)
        phis = []
        t = N * pm  # Phi(1); mpf has no overflow, so the recurrence is safe for any N
        for k in range(1, N + 1):
            phis.append(t)
            t = t * pm * ((N - k) * k) / (k + 1)
        for s in sp.shapes:
            we = pm ** shape_excess(s) if sp.weighting == "length" else ctx.mpf(1)
            row = []
            for k in range(1, N + 1):
                r = sp.ratio(s, k)
                row.append(phis[k - 1] * we * r.numerator / r.denominator if r
                           else ctx.mpf(0))
            joint[s] = row
        s0 = ctx.fsum(v for row in joint.values() for v in row)
        joint = {s: [v / s0 for v in row] for s, row in joint.items()}
        totals = {s: ctx.fsum(row) for s, row in joint.items()}
    joint = {s: [export(v, dps) for v in row] for s, row in joint.items()}
    totals = {s: export(v, dps) for s, v in totals.items()}
    return ClassDecomposition(dist, sp.shapes, joint, totals)


def class_probabilities(N: int, p: Any, *, space: str | Space = "eq41",
                        dps: int = DEFAULT_DPS,
                        weighting: str | None = None) -> dict[str, Any]:
    """``{paper label: P(class)}`` (the "probability of observing each class", figure 11).

    >>> class_probabilities(4, Fraction(1, 2), space="eq41-printed")["phi^{1,0,0}"]
    Fraction(4, 39)
    """
    cd = class_decomposition(N, p, space=space, dps=dps, weighting=weighting)
    return {cd.labels[s]: cd.totals[s] for s in cd.shapes}
