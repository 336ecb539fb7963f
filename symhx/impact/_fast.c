/* Float64 impact engine for symhx.impact: a line-by-line port of symhx/impact/engine.py
 * (see its docstring for the algorithm: certified first-root search over closed-form flight,
 * grazing, sequential simultaneous impacts, chatter -> sticking, release).
 * Plain Python C API (no numpy headers), so `pip install .` needs only a C compiler. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TOLF 64.0
#define EPS 2.220446049250313e-16
#define MAXIT 1000000
#define CRAWL 100000   /* engine._CRAWL */
enum { S_NONE, S_CONT, S_ROOT, S_GRAZE, S_NOW };
enum { K_IMPACT, K_GRAZE, K_STICK, K_RELEASE };

typedef struct {
    int n, nf, L;
    double om, d, r, vstick, chunk, tend, t_from;
    const double *F;
    double *coef, *forced, *raw;
    unsigned char *stuck;
    double *nt;
    int *nk;
    int *heap, *hpos;         /* binary min-heap of the sites by (nt, site) and their positions */
    int record;
    long long *counts;
    double *ev;
    size_t nev, cap_ev;
    double *up;
    size_t nup, cap_up;
    long long nevents, max_events;
    double *g;
    double *gc, *bc;          /* per site: the searched polynomial and its bounds (c0, S, M1..M4),
                               * valid until the site is next rescheduled from scratch */
    double *F2, *F3;          /* F_m^2, F_m^3 */
    double *tc;               /* trig cache: 2 slots of [cos(F_m t)..., sin(F_m t)...] */
    double tc_t[2], pin;      /* slot times; slot 0 holds the pinned (current event) time */
    double plastic_at;        /* instant at which the cascade backstop is active (else NAN) */
    int err;
    char errmsg[200];
} Eng;

/* cos and sin of x: Cody-Waite reduction by pi/2 to the nearest multiple (three 33-bit parts,
 * exact products for |x| < 2^19 pi/2; the two small ones summed first) and the fdlibm minimax polynomials on [-pi/4, pi/4], their tails by Estrin's
 * scheme (shorter latency than Horner; absolute error < 2^-52, far inside the 64 eps rounding
 * bounds of the search).  engine._cos_sin is the same sequence of IEEE operations in Python, so
 * the float64 engines stay identical; larger |x| use libm in both. */
static inline void cos_sin(double x, double *c, double *s) {
    if (!(fabs(x) < 823549.6)) { *c = cos(x); *s = sin(x); return; }
    /* nearest integer to x 2/pi by the 1.5 * 2^52 shift (|x 2/pi| < 2^19: exact) */
    double fn = (x * 6.36619772367581382433e-01 + 6755399441055744.0) - 6755399441055744.0;
    double y = (x - fn * 1.57079632673412561417e+00)
        - (fn * 6.07710050630396597660e-11 + fn * 2.02226624871116645580e-21);
    double z = y * y, z2 = z * z, z4 = z2 * z2;
    double sr = (8.33333333332248946124e-03 + z * -1.98412698298579493134e-04)
        + (z2 * (2.75573137070700676789e-06 + z * -2.50507602534068634195e-08)
           + z4 * 1.58969099521155010221e-10);
    double sv = y + (z * y * -1.66666666666666324348e-01 + z2 * y * sr);
    double cp = (4.16666666666666019037e-02 + z * -1.38888888888741095749e-03)
        + (z2 * (2.48015872894767294178e-05 + z * -2.75573143513906633035e-07)
           + z4 * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11));
    double hz = 0.5 * z, w = 1.0 - hz;
    double cv = w + (((1.0 - w) - hz) + z2 * cp);
    switch (((long long)fn) & 3) {
    case 0: *c = cv; *s = sv; break;
    case 1: *c = -sv; *s = cv; break;
    case 2: *c = -cv; *s = -sv; break;
    default: *c = sv; *s = -cv; break;
    }
}

#if defined(__GNUC__) || defined(__clang__)
#define HAVE_V2D 1
typedef double v2d __attribute__((vector_size(16)));
typedef long long v2di __attribute__((vector_size(16)));

static inline void quadrant(double fn, double cv, double sv, double *c, double *s) {
    switch (((long long)fn) & 3) {
    case 0: *c = cv; *s = sv; break;
    case 1: *c = -sv; *s = cv; break;
    case 2: *c = -cv; *s = -sv; break;
    default: *c = sv; *s = -cv; break;
    }
}

/* cos_sin of two arguments at once: the same IEEE operations as cos_sin in each lane (two-lane
 * SIMD multiplies and adds round exactly like the scalar ones; no contraction, see setup.py), so
 * bit-identical results at about half the cost. */
static inline void cos_sin2(double x0, double x1, double *c0, double *s0, double *c1, double *s1) {
    if (!(fabs(x0) < 823549.6 && fabs(x1) < 823549.6)) {
        cos_sin(x0, c0, s0);
        cos_sin(x1, c1, s1);
        return;
    }
    v2d x = {x0, x1};
    v2d fn = (x * 6.36619772367581382433e-01 + 6755399441055744.0) - 6755399441055744.0;
    double f0 = fn[0], f1 = fn[1];
    v2d y = (x - fn * 1.57079632673412561417e+00)
        - (fn * 6.07710050630396597660e-11 + fn * 2.02226624871116645580e-21);
    v2d z = y * y, z2 = z * z, z4 = z2 * z2;
    v2d sr = (8.33333333332248946124e-03 + z * -1.98412698298579493134e-04)
        + (z2 * (2.75573137070700676789e-06 + z * -2.50507602534068634195e-08)
           + z4 * 1.58969099521155010221e-10);
    v2d sv = y + (z * y * -1.66666666666666324348e-01 + z2 * y * sr);
    v2d cp = (4.16666666666666019037e-02 + z * -1.38888888888741095749e-03)
        + (z2 * (2.48015872894767294178e-05 + z * -2.75573143513906633035e-07)
           + z4 * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11));
    v2d hz = 0.5 * z, w = 1.0 - hz;
    v2d cv = w + (((1.0 - w) - hz) + z2 * cp);
    quadrant(f0, cv[0], sv[0], c0, s0);
    quadrant(f1, cv[1], sv[1], c1, s1);
}
#endif

/* cos(F_m t), sin(F_m t) for all m: the same libm values as a direct call, computed once per
 * distinct t (the event time is pinned: the impact, the kicks and every re-search start there). */
static const double *trig(Eng *E, double t) {
    if (t == E->tc_t[0]) return E->tc;
    int nf = E->nf;
    if (t == E->tc_t[1]) return E->tc + 2 * nf;
    int k = (t == E->pin) ? 0 : 1;
    double *c = E->tc + 2 * k * nf;
    int m = 0;
#ifdef HAVE_V2D
    for (; m + 1 < nf; m += 2) {
        cos_sin2(E->F[m] * t, E->F[m + 1] * t, c + m, c + nf + m, c + m + 1, c + nf + m + 1);
    }
#endif
    for (; m < nf; m++) {
        cos_sin(E->F[m] * t, c + m, c + nf + m);
    }
    E->tc_t[k] = t;
    return c;
}

static void derivs(Eng *E, const double *g, double t, double *D, double *V, double *A,
                   double *J) {
    double d = g[0], v = 0, a = 0, j = 0;
    int nf = E->nf;
    const double *cs = trig(E, t);
    for (int m = 0; m < nf; m++) {
        double ca = g[1 + 2 * m], cb = g[2 + 2 * m];
        if (ca == 0.0 && cb == 0.0) continue;
        double f = E->F[m], c = cs[m], s = cs[nf + m];
        double p = ca * c + cb * s, q = cb * c - ca * s;
        d += p;
        v += f * q;
        a -= E->F2[m] * p;
        j -= E->F3[m] * q;
    }
    *D = d; *V = v; *A = a; *J = j;
}

static void bounds(Eng *E, const double *g, double *c0, double *S, double *M1, double *M2,
                   double *M3, double *M4) {
    double c00 = g[0], s = 0, m1 = 0, m2 = 0, m3 = 0, m4 = 0;
    for (int m = 0; m < E->nf; m++) {
        double f = E->F[m];
        if (f == 0.0) { c00 += g[1 + 2 * m]; continue; }
        double ga = g[1 + 2 * m], gb = g[2 + 2 * m], c = sqrt(ga * ga + gb * gb);
        s += c; m1 += c * f; m2 += c * f * f; m3 += c * f * f * f; m4 += c * f * f * f * f;
    }
    *c0 = c00; *S = s; *M1 = m1; *M2 = m2; *M3 = m3; *M4 = m4;
}

/* scaleD = |c0| + S, M1: the bounds of g (as computed by search); D0, V0, A0, J0: g, g', g'',
 * g''' at lo (already evaluated by the caller: the same values derivs would return) */
static double refine(Eng *E, const double *g, double lo, double hi, double scaleD, double M1,
                     double D0, double V0, double A0, double J0) {
    double D = D0, V = V0, A = A0, J = J0, x = lo;
    for (int it = 0; it < 400; it++) {
        if (it) derivs(E, g, x, &D, &V, &A, &J);
        if (fabs(D) <= TOLF * EPS * (scaleD + M1 * fabs(x)) && V < 0) return x - D / V;
        if (D > 0) lo = x;
        else if (D < 0) hi = x;
        else return x;
        double xn;
        if (V < 0) {   /* Householder order 3, else Halley, else Newton (engine.refine) */
            double den3 = 6 * V * V * V - 6 * D * V * A + D * D * J;
            if (den3 < 0) xn = x - D * (6 * V * V - 3 * D * A) / den3;
            else {
                double den = 2 * V * V - D * A;
                xn = den > 0 ? x - 2 * D * V / den : x - D / V;
            }
        } else xn = 0.5 * (lo + hi);
        if (!(lo < xn && xn < hi)) xn = 0.5 * (lo + hi);
        if (fabs(xn - x) <= 2 * EPS * fabs(xn) || hi - lo <= 4 * EPS * fabs(hi)) return xn;
        x = xn;
    }
    return x;
}

/* Dt, Vt, At, Jt: g, g', g'', g''' at t (evaluated by search) */
static int graze(Eng *E, const double *g, double t, double t0, double tolD, double scaleD,
                 double M1, double Dt, double Vt, double At, double Jt, double *te) {
    double tg = t, D, V = Vt, A = At, J;
    for (int it = 0; it < 100; it++) {
        if (it) derivs(E, g, tg, &D, &V, &A, &J);
        if (A <= 0) break;
        double step = V / A;
        tg -= step;
        if (fabs(step) <= 4 * EPS * (fabs(tg) + 1)) break;
    }
    if (tg < t0) tg = t;
    if (tg == t) D = Dt;
    else derivs(E, g, tg, &D, &V, &A, &J);
    if (D < -tolD && tg > t) { *te = refine(E, g, t, tg, scaleD, M1, Dt, Vt, At, Jt); return S_ROOT; }
    *te = tg;
    return S_GRAZE;
}

/* b: the bounds of g (c0, S, M1, M2, M3, M4) */
static int search(Eng *E, const double *g, const double *b, double t0, double thi, int is_gap,
                  int graze_restart, double *te) {
    double c0 = b[0], S = b[1], M1 = b[2], M2 = b[3], M3 = b[4], M4 = b[5], D, V, A, J;
    double scale0 = fabs(c0) + S;
    if (M2 == 0) {
        if (c0 > TOLF * EPS * fabs(c0)) { *te = INFINITY; return S_NONE; }
        *te = t0; return S_NOW;
    }
    if (c0 - S > TOLF * EPS * scale0) { *te = INFINITY; return S_NONE; }
    double t = t0, iM2 = 1 / M2, M3_3 = M3 / 3;
    int first = 1;
    for (long it = 0; it < MAXIT; it++) {
        if (t >= thi) { *te = t; return S_CONT; }   /* certified up to t >= thi: resume there */
        derivs(E, g, t, &D, &V, &A, &J);
        double at = fabs(t);
        double tolD = TOLF * EPS * (scale0 + M1 * at), tolV = TOLF * EPS * (M1 + M2 * at);
        double tolA = TOLF * EPS * (M2 + M3 * at), tolJ = TOLF * EPS * (M3 + M4 * at);
        if (first) {
            first = 0;
            /* a gap overlapping (by rounding), not opening; a contact force clearly tensile,
             * rising or not: contact now (a release at once) -- engine.Engine.search */
            if (D < -tolD && !(is_gap && V > tolV)) { *te = t; return S_NOW; }
            if (D <= tolD) {
                double h;
                if (graze_restart && V < 0) V = 0;
                if (V < -tolV) { *te = t; return S_NOW; }
                if (V > tolV) {
                    if (is_gap && V <= E->vstick && A < -tolA) { *te = t; return S_NOW; }
                    double Vl = V - tolV, Al = A - tolA;
                    h = (Al / 2 + sqrt(Al * Al / 4 + 2 * Vl * M3 / 3)) / (M3 / 3);
                } else if (A < -tolA) { *te = t; return S_NOW; }
                else if (A > tolA) h = 3 * (A - tolA) / M3;
                else if (J < -tolJ) { *te = t; return S_NOW; }
                else if (J > tolJ) h = 4 * (J - tolJ) / M4;
                else {
                    E->err = 1;
                    snprintf(E->errmsg, sizeof E->errmsg,
                             "degenerate contact at t=%.17g: value and three derivatives vanish", t);
                    *te = t; return S_NONE;
                }
                t = t + h * 0.75;
                continue;
            }
        } else if (D <= tolD || it == CRAWL) {   /* or hovering just above zero: a touch */
            if (V < -tolV && (A <= 0 || V * V > 8 * M2 * tolD)) {
                double Dz = D > 0 ? D : 0;   /* first root of D + V s + A s^2/2 (engine.py) */
                *te = t + 2 * Dz / (-V + sqrt(V * V - 2 * A * Dz)); return S_ROOT;
            }
            if (A < -tolA && V <= tolV) { *te = t; return S_NOW; }
            return graze(E, g, t, t0, tolD, scale0, M1, D, V, A, J, te);
        }
        double Dl = D - tolD;
        if (V < 0) {
            double Vm = -V - tolV, Dp = D + tolD;
            if (Vm > 0 && 2 * M2 * Dp < Vm * Vm) {
                *te = refine(E, g, t, t + 2 * Dp / Vm, scale0, M1, D, V, A, J);
                return S_ROOT;
            }
        }
        double Vl = V - tolV;
        double h = (Vl + sqrt(Vl * Vl + 2 * M2 * Dl)) * iM2;
        double Al = A - tolA, H = 2 * h;
        for (int k = 0; k < 5; k++) {
            double c = (Al - M3_3 * H) * 0.5;
            if (Dl + Vl * H + c * H * H <= 0) break;
            if (c > 0 && Vl < 0 && -Vl < 2 * c * H && 4 * c * Dl <= Vl * Vl) break;
            h = H;
            H = 2 * H;
        }
        t = t + h;
    }
    E->err = 1;
    snprintf(E->errmsg, sizeof E->errmsg, "root search did not finish (t=%.17g)", t);
    *te = t;
    return S_NONE;
}

/* ------------------------------------------------------------------ bodies */
static void body(const Eng *E, int j, int *lo, int *hi) {
    int a = j, b = j;
    while (a > 0 && E->stuck[a - 1]) a--;
    while (b < E->n + 1 && E->stuck[b]) b++;
    *lo = a; *hi = b;
}

static int grow(double **buf, size_t *cap, size_t need) {
    if (need <= *cap) return 0;
    size_t nc = *cap ? *cap : 1024;
    while (nc < need) nc *= 2;
    double *p = realloc(*buf, nc * sizeof(double));
    if (!p) return -1;
    *buf = p; *cap = nc;
    return 0;
}

static void record_update(Eng *E, int j, double t) {
    if (!E->record) return;
    size_t w = 2 + E->L;
    if (grow(&E->up, &E->cap_up, (E->nup + 1) * w)) { E->err = 2; return; }
    double *p = E->up + E->nup * w;
    p[0] = j; p[1] = t;
    memcpy(p + 2, E->coef + (size_t)j * E->L, E->L * sizeof(double));
    E->nup++;
}

/* one event record: the layout of engine.EVENT_DTYPE (48 bytes, numpy reads the fields as
 * arrays without copies) */
typedef struct {
    double t;
    long long site;
    signed char kind, pad[7];
    double u0, u1, aux;
} EvRec;
typedef char evrec_is_48_bytes[sizeof(EvRec) == 6 * sizeof(double) ? 1 : -1];

static void record_event(Eng *E, double t, int site, int kind, double u0, double u1, double aux) {
    if (kind == K_IMPACT || kind == K_STICK) {
        if (t >= E->t_from) E->counts[site]++;
    }
    if (!E->record) return;
    if (grow(&E->ev, &E->cap_ev, (E->nev + 1) * 6)) { E->err = 2; return; }
    EvRec *p = (EvRec *)(E->ev + E->nev * 6);
    memset(p, 0, sizeof *p);
    p->t = t; p->site = site; p->kind = (signed char)kind; p->u0 = u0; p->u1 = u1; p->aux = aux;
    E->nev++;
}

static void set_motion(Eng *E, int lo, int hi, double t, double X, double Vel) {
    int n = E->n, L = E->L;
    double *c = E->g;
    memset(c, 0, L * sizeof(double));
    if (lo == 0) {
    } else if (hi == n + 1) {
        c[0] = (n + 1) * E->d;
    } else {
        int m = hi - lo + 1;
        for (int k = 0; k < L; k++) {
            double s = 0;
            for (int j = lo; j <= hi; j++) s += E->forced[(size_t)j * L + k];
            c[k] = s / m;
        }
        c[0] = (lo + hi) * E->d / 2;
        double fx, fv, A, J;
        derivs(E, c, t, &fx, &fv, &A, &J);
        double y = X - fx, yv = (Vel - fv) / E->om;
        const double *tr = trig(E, t);   /* F[0] = omega */
        double cs = tr[0], sn = tr[E->nf];
        c[1] = y * cs - yv * sn;
        c[2] = y * sn + yv * cs;
    }
    int a = lo > 1 ? lo : 1, b = hi < n ? hi : n;
    for (int j = a; j <= b; j++) {
        memcpy(E->coef + (size_t)j * L, c, L * sizeof(double));
        record_update(E, j, t);
    }
}

static void kick(Eng *E, int lo, int hi, double t, double dv) {
    const double *tr = trig(E, t);   /* F[0] = omega */
    double cs = tr[0], sn = tr[E->nf];
    int a = lo > 1 ? lo : 1, b = hi < E->n ? hi : E->n;
    for (int j = a; j <= b; j++) {
        double *c = E->coef + (size_t)j * E->L;
        c[1] -= dv * sn / E->om;
        c[2] += dv * cs / E->om;
        record_update(E, j, t);
    }
}

static void contact_force(Eng *E, int k, double *out) {
    int lo, hi, n = E->n, L = E->L;
    body(E, k, &lo, &hi);
    double om2d = E->om * E->om * E->d;
    memset(out, 0, L * sizeof(double));
    if (lo == 0) {
        for (int j = k + 1; j <= hi; j++) {
            out[0] -= om2d * j;
            for (int q = 3; q < L; q++) out[q] -= E->raw[(size_t)j * L + q];
        }
    } else if (hi == n + 1) {
        for (int j = lo; j <= k; j++) {
            out[0] -= om2d * (n + 1 - j);
            for (int q = 3; q < L; q++) out[q] += E->raw[(size_t)j * L + q];
        }
    } else {
        int m = hi - lo + 1, jbar2 = lo + hi;
        for (int q = 3; q < L; q++) {
            double fbar = 0;
            for (int j = lo; j <= hi; j++) fbar += E->raw[(size_t)j * L + q];
            fbar /= m;
            for (int j = lo; j <= k; j++) out[q] += E->raw[(size_t)j * L + q] - fbar;
        }
        for (int j = lo; j <= k; j++) out[0] += om2d * (2 * j - jbar2) / 2.0;
    }
}

static void gap_poly(const Eng *E, int i, double *out) {
    const double *a = E->coef + (size_t)i * E->L, *b = E->coef + (size_t)(i + 1) * E->L;
    for (int q = 0; q < E->L; q++) out[q] = b[q] - a[q];
}

/* ------------------------------------------------------------------ event queue
 * An indexed binary min-heap of the sites keyed by (next event time, stuck, site): the earliest
 * event; at one instant the free gaps (impacts) before the stuck ones (releases), then the
 * smallest site (the key of the reference engine's linear scan, engine.Engine.run).  Only the
 * re-searched sites move in it: O(log n) per event instead of a scan of all n + 1 sites. */
static inline int hless(const Eng *E, int a, int b) {
    double ta = E->nt[a], tb = E->nt[b];
    if (ta != tb) return ta < tb;
    /* one instant: free gaps (impacts) before stuck ones (releases), then the smallest site */
    if (E->stuck[a] != E->stuck[b]) return E->stuck[a] < E->stuck[b];
    return a < b;
}

/* move site i to its place after its key changed: sift up or down through a hole (the moved
 * sites are written once each, the key of i is compared against theirs) */
static void hfix(Eng *E, int i) {
    int p = E->hpos[i], size = E->n + 1, *heap = E->heap, *hpos = E->hpos;
    while (p > 0) {
        int q = (p - 1) / 2, h = heap[q];
        if (!hless(E, i, h)) break;
        heap[p] = h; hpos[h] = p;
        p = q;
    }
    for (;;) {
        int l = 2 * p + 1;
        if (l >= size) break;
        int h = heap[l];
        if (l + 1 < size && hless(E, heap[l + 1], h)) { l++; h = heap[l]; }
        if (!hless(E, h, i)) break;
        heap[p] = h; hpos[h] = p;
        p = l;
    }
    heap[p] = i; hpos[i] = p;
}

/* earliest scheduled time of the sites other than i (the heap's top, or its best child) */
static inline double next_other(const Eng *E, int i) {
    int h = E->heap[0], size = E->n + 1;
    if (h != i) return E->nt[h];
    double a = size > 1 ? E->nt[E->heap[1]] : INFINITY, b = size > 2 ? E->nt[E->heap[2]] : INFINITY;
    return a < b ? a : b;
}

static void schedule(Eng *E, int i, double t, int graze_restart, int reuse) {
    double thi = t + E->chunk, te;
    if (thi > E->tend) thi = E->tend;
    double tn = next_other(E, i);   /* engine.Engine.run.schedule: search no further than that */
    if (tn > t && tn < thi) thi = tn;
    double *g = E->gc + (size_t)i * E->L, *b = E->bc + (size_t)i * 6;
    if (!reuse) {
        if (E->stuck[i]) contact_force(E, i, g);
        else gap_poly(E, i, g);
        bounds(E, g, b, b + 1, b + 2, b + 3, b + 4, b + 5);
    }
    int code = search(E, g, b, t, thi, !E->stuck[i], graze_restart, &te);
    if (code == S_CONT && te >= E->tend) { te = INFINITY; code = S_NONE; }
    E->nt[i] = te;
    E->nk[i] = code;
    hfix(E, i);
}

static void pos_vel(Eng *E, int j, double t, double *x, double *v) {
    double A, J;
    derivs(E, E->coef + (size_t)j * E->L, t, x, v, &A, &J);
}

static void stick(Eng *E, int i, int lo, int hi, double t, double u, double A, int mL, int mR) {
    double aux = (E->r < 1 && A < 0) ? t + 2 * u / ((-A) * (1 - E->r)) : t;
    double X, Vel;
    if (lo == 0) { X = 0; Vel = 0; }
    else if (hi == E->n + 1) { X = (E->n + 1) * E->d; Vel = 0; }
    else {
        double xL, vL, xR, vR;
        pos_vel(E, i, t, &xL, &vL);
        pos_vel(E, i + 1, t, &xR, &vR);
        X = (mL * xL + mR * xR) / (double)(mL + mR);
        Vel = (mL * vL + mR * vR) / (double)(mL + mR);
    }
    E->stuck[i] = 1;
    hfix(E, i);
    set_motion(E, lo, hi, t, X, Vel);
    record_event(E, t, i, K_STICK, -u, 0.0, aux);
}

static void impact(Eng *E, int i, double t, int *plo, int *phi) {
    int lo, hi, tmp;
    body(E, i, &lo, &tmp);
    body(E, i + 1, &tmp, &hi);
    *plo = lo; *phi = hi;
    const double *g = E->gc + (size_t)i * E->L, *b = E->bc + (size_t)i * 6;   /* = gap_poly, bounds */
    double D, u, A, J, M2 = b[3], M3 = b[4];
    derivs(E, g, t, &D, &u, &A, &J);
    double tolA = TOLF * EPS * (M2 + M3 * fabs(t));
    int compressive = A < -tolA || (fabs(A) <= tolA && J < 0);
    int wallL = (lo == 0), wallR = (hi == E->n + 1);
    int mL = i - lo + 1, mR = hi - i;
    double r = E->r;
    int plastic = (r == 0.0) || (t == E->plastic_at);
    if (fabs(u) <= E->vstick) {   /* below the chatter threshold: the bodies move together */
        stick(E, i, lo, hi, t, r * fabs(u), A, mL, mR);
        return;
    }
    if (u >= 0) { record_event(E, t, i, K_GRAZE, u, u, 0.0); return; }
    double u1 = -r * u, dvL, dvR;
    if (wallL) { dvL = 0; dvR = -(1 + r) * u; }
    else if (wallR) { dvL = (1 + r) * u; dvR = 0; }
    else {
        dvL = (1 + r) * u * mR / (double)(mL + mR);
        dvR = -(1 + r) * u * mL / (double)(mL + mR);
    }
    if (!wallL) kick(E, lo, i, t, dvL);
    if (!wallR) kick(E, i + 1, hi, t, dvR);
    record_event(E, t, i, K_IMPACT, u, u1, 0.0);
    if (plastic || (u1 <= E->vstick && compressive)) stick(E, i, lo, hi, t, fabs(u1), A, mL, mR);
}

static void run(Eng *E) {
    int n = E->n;
    for (int i = 0; i <= n; i++) {
        E->nt[i] = INFINITY;
        E->heap[i] = i;
        E->hpos[i] = i;
    }
    for (int i = 0; i <= n; i++) schedule(E, i, 0.0, 0, 0);
    double last_t = NAN, lg_t = NAN, lm_t = NAN;
    long same = 0;
    int lg_i = -1, lm_i = -1;
    while (!E->err) {
        int i = E->heap[0];
        double te = E->nt[i];
        if (!(te <= E->tend)) break;
        int code = E->nk[i];
        if (te == last_t) {
            long bound = 20L * (n + 1) + 100;   /* engine.cascade_bound */
            if (++same == bound) E->plastic_at = te;   /* backstop: rest of the instant plastic */
            else if (same > 2 * bound) {
                E->err = 1;
                snprintf(E->errmsg, sizeof E->errmsg,
                         "more than %ld events at t=%.17g even with plastic impacts: degenerate "
                         "contact configuration", same, te);
                break;
            }
        } else { same = 0; last_t = te; }
        double t = te;
        E->pin = t;
        if (code == S_CONT) { schedule(E, i, t, 0, 1); continue; }
        E->nevents++;
        if (E->max_events > 0 && E->nevents > E->max_events) {
            E->err = 3;
            snprintf(E->errmsg, sizeof E->errmsg, "more than max_events=%lld events before t_end",
                     E->max_events);
            break;
        }
        int lo, hi;
        if (E->stuck[i]) {
            if (code == S_GRAZE) { schedule(E, i, t, 1, 1); continue; }
            body(E, i, &lo, &hi);
            double X = 0, Vel = 0;
            if (lo != 0) pos_vel(E, lo, t, &X, &Vel);
            E->stuck[i] = 0;
            hfix(E, i);
            set_motion(E, lo, i, t, X, Vel);
            set_motion(E, i + 1, hi, t, X, Vel);
            record_event(E, t, i, K_RELEASE, 0.0, 0.0, t);
        } else if (code == S_GRAZE) {
            double D, V, A, J;
            derivs(E, E->gc + (size_t)i * E->L, t, &D, &V, &A, &J);   /* cached gap_poly */
            record_event(E, t, i, K_GRAZE, V, V, D);
            const double *b = E->bc + (size_t)i * 6;   /* bounds of the cached gap_poly */
            double tolD = TOLF * EPS * (fabs(b[0]) + b[1] + b[2] * fabs(t));
            double h = b[4] > 0 ? pow(6 * tolD / b[4], 1.0 / 3.0) : E->chunk;   /* = engine.touch_step */
            /* "the same touch": the same site within one touch step (engine.py; t is never earlier) */
            if (i == lm_i && t < lm_t + h) {   /* merged and released: step past */
                schedule(E, i, t + h, 1, 1);
                continue;
            }
            if (i == lg_i && t < lg_t + h) {   /* the same touch again: together */
                lm_t = t; lm_i = i;
                int tmp;
                body(E, i, &lo, &tmp);
                body(E, i + 1, &tmp, &hi);
                stick(E, i, lo, hi, t, 0.0, A, i - lo + 1, hi - i);
            } else {
                lg_t = t; lg_i = i;
                schedule(E, i, t, 1, 1);
                continue;
            }
        } else {
            impact(E, i, t, &lo, &hi);
        }
        int a = lo - 1 > 0 ? lo - 1 : 0, b = hi < n ? hi : n;
        for (int k = a; k <= b; k++) schedule(E, k, t, 0, 0);
    }
}

/* The closed-form arrays of a row from its float64 inputs: the same IEEE operations in the same
 * order as the float64 path of engine.row_arrays (tests check bit-identity), so the C engine pays
 * its own set-up without numpy.  F = (omega, Omega_1..Omega_K); alpha, beta: n x K (C order). */
static void row_setup(Eng *E, const double *alpha, const double *beta, const double *x0,
                      const double *v0) {
    int n = E->n, K = E->nf - 1, L = E->L;
    size_t sz = (size_t)(n + 2) * L;
    memset(E->coef, 0, sz * sizeof(double));
    memset(E->forced, 0, sz * sizeof(double));
    memset(E->raw, 0, sz * sizeof(double));
    double om = E->om, om2 = om * om;
    for (int j = 1; j <= n; j++) {
        const double *a = alpha + (size_t)(j - 1) * K, *b = beta + (size_t)(j - 1) * K;
        double *fo = E->forced + (size_t)j * L, *ra = E->raw + (size_t)j * L;
        double fx = 0, fv = 0;
        for (int m = 0; m < K; m++) {
            double f = E->F[m + 1], den = om2 - f * f;
            double fa = a[m] / den, fb = b[m] / den;
            fo[3 + 2 * m] = fa; fo[4 + 2 * m] = fb;
            ra[3 + 2 * m] = a[m]; ra[4 + 2 * m] = b[m];
            fx = m == 0 ? fa : fx + fa;
            fv = m == 0 ? fb * f : fv + fb * f;
        }
        double *c = E->coef + (size_t)j * L, jd = (double)j * E->d;
        memcpy(c, fo, L * sizeof(double));
        c[0] = jd;
        c[1] = (x0[j - 1] - jd) - fx;
        c[2] = (v0[j - 1] - fv) / om;
    }
    E->coef[(size_t)(n + 1) * L] = (double)(n + 1) * E->d;
}

/* run(n, omega, d, r, v_stick, t_end, t_from, record, max_events, F, alpha, beta, x0, v0)
 * F: sequence of the nf = K + 1 frequencies (omega, Omega_1..Omega_K) as floats; alpha, beta:
 * buffers of n*K doubles (C order), x0, v0: n doubles.  The search horizon is engine.row_arrays'
 * chunk 2 / omega.
 * -> (counts bytes (n+1) int64, events bytes, updates bytes, n_events, coef0 bytes or None)
 * (coef0: the (n+2) x L coefficients at t = 0, returned when record) */
static PyObject *py_run(PyObject *self, PyObject *args) {
    int n, record;
    double om, d, r, vstick, tend, tfrom;
    long long max_events;
    PyObject *Fobj;
    Py_buffer ba, bb, bx, bv;
    if (!PyArg_ParseTuple(args, "iddddddpLOy*y*y*y*", &n, &om, &d, &r, &vstick, &tend, &tfrom,
                          &record, &max_events, &Fobj, &ba, &bb, &bx, &bv))
        return NULL;
    Eng E;
    memset(&E, 0, sizeof E);
    PyObject *res = NULL, *Fseq = NULL, *coef0 = NULL;
    double *Fv = NULL;
    if (n < 1) {
        PyErr_SetString(PyExc_ValueError, "n must be >= 1");
        goto done;
    }
    Fseq = PySequence_Fast(Fobj, "F must be a sequence of floats");
    if (!Fseq) goto done;
    E.nf = (int)PySequence_Fast_GET_SIZE(Fseq);
    if (E.nf < 2) {
        PyErr_SetString(PyExc_ValueError, "F must hold omega and at least one forcing frequency");
        goto done;
    }
    Fv = malloc(E.nf * sizeof(double));
    if (!Fv) { PyErr_NoMemory(); goto done; }
    for (int m = 0; m < E.nf; m++) {
        Fv[m] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(Fseq, m));
        if (Fv[m] == -1.0 && PyErr_Occurred()) goto done;
    }
    int K = E.nf - 1;
    if ((size_t)ba.len != (size_t)n * K * sizeof(double) || ba.len != bb.len
        || (size_t)bx.len != (size_t)n * sizeof(double) || bx.len != bv.len) {
        PyErr_SetString(PyExc_ValueError, "alpha, beta, x0 or v0 has the wrong size");
        goto done;
    }
    E.n = n; E.om = om; E.d = d; E.r = r; E.vstick = vstick; E.chunk = 2 / om; E.tend = tend;
    E.t_from = tfrom; E.record = record; E.max_events = max_events;
    E.L = 1 + 2 * E.nf;
    E.F = Fv;
    size_t sz = (size_t)(n + 2) * E.L * sizeof(double);
    /* one block for every per-run array (fewer allocator calls): doubles first, then ints */
    size_t nd = 3 * sz / sizeof(double) + (n + 1) + E.L + (size_t)(n + 1) * E.L
                + (size_t)(n + 1) * 6 + 2 * E.nf + 4 * E.nf;
    size_t ni = 3 * (size_t)(n + 1);
    char *blk = malloc(nd * sizeof(double) + ni * sizeof(int) + (n + 1)
                       + (n + 1) * sizeof(long long));
    if (!blk) { PyErr_NoMemory(); goto done; }
    double *p = (double *)blk;
    E.coef = p; p += sz / sizeof(double);
    E.forced = p; p += sz / sizeof(double);
    E.raw = p; p += sz / sizeof(double);
    E.nt = p; p += n + 1;
    E.g = p; p += E.L;
    E.gc = p; p += (size_t)(n + 1) * E.L;
    E.bc = p; p += (size_t)(n + 1) * 6;
    E.F2 = p; p += E.nf;
    E.F3 = p; p += E.nf;
    E.tc = p; p += 4 * E.nf;
    E.counts = (long long *)p;
    int *q = (int *)(E.counts + (n + 1));
    E.nk = q; q += n + 1;
    E.heap = q; q += n + 1;
    E.hpos = q; q += n + 1;
    E.stuck = (unsigned char *)q;
    memset(E.stuck, 0, n + 1);
    memset(E.counts, 0, (n + 1) * sizeof(long long));
    E.tc_t[0] = E.tc_t[1] = NAN;
    E.pin = 0.0;
    E.plastic_at = NAN;
    for (int m = 0; m < E.nf; m++) {
        E.F2[m] = E.F[m] * E.F[m];
        E.F3[m] = E.F2[m] * E.F[m];
    }
    row_setup(&E, (const double *)ba.buf, (const double *)bb.buf, (const double *)bx.buf,
              (const double *)bv.buf);
    if (record) {
        coef0 = PyBytes_FromStringAndSize((const char *)E.coef, (Py_ssize_t)sz);
        if (!coef0) goto done;
    }
    Py_BEGIN_ALLOW_THREADS
    run(&E);
    Py_END_ALLOW_THREADS
    if (E.err == 2) { PyErr_NoMemory(); goto done; }
    if (E.err) { PyErr_SetString(PyExc_RuntimeError, E.errmsg); goto done; }
    res = Py_BuildValue("(y#y#y#LO)", (const char *)E.counts, (Py_ssize_t)((n + 1) * sizeof(long long)),
                        (const char *)E.ev, (Py_ssize_t)(E.nev * 6 * sizeof(double)),
                        (const char *)E.up, (Py_ssize_t)(E.nup * (2 + E.L) * sizeof(double)),
                        E.nevents, coef0 ? coef0 : Py_None);
done:
    free(E.coef);   /* the block */
    free(Fv); free(E.ev); free(E.up);
    Py_XDECREF(Fseq); Py_XDECREF(coef0);
    PyBuffer_Release(&ba); PyBuffer_Release(&bb); PyBuffer_Release(&bx); PyBuffer_Release(&bv);
    return res;
}

static PyMethodDef methods[] = {
    {"run", py_run, METH_VARARGS, "Run the float64 impact engine (see symhx.impact.fast)."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef moddef = {PyModuleDef_HEAD_INIT, "_fast",
                                    "Float64 impact engine (C).", -1, methods};

/* SHA-256 of this file, passed by setup.py: symhx.impact.fast.source_sha256() reads it and a test
 * compares it with _fast.c on disk (a stale build is caught, not used) */
#ifndef SYMHX_FAST_SOURCE_SHA256
#define SYMHX_FAST_SOURCE_SHA256 "unknown"
#endif

PyMODINIT_FUNC PyInit__fast(void) {
    PyObject *m = PyModule_Create(&moddef);
    if (m && PyModule_AddStringConstant(m, "source_sha256", SYMHX_FAST_SOURCE_SHA256) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
