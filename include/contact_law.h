/* Frictional contact of slave nodes with rigid tools: penalty normal force, Coulomb friction
   integrated by return mapping (eqs 14-18 of the method), its consistent tangent (eq 23), nodal
   forces (eq 25) and the local tangent frame recurrence (eqs 28-30).

   Conventions (doc/notes/contact-log.md):
   * n is the unit normal of the tool surface at the closest point, pointing out of the tool;
     g = (y - x).n is the gap, negative when the node has penetrated the tool.
   * t_N = K_N max(0, -g) >= 0 (compression positive); with an augmented-Lagrangian multiplier
     lN, t_N = max(0, lN - K_N g).
   * The slip increment of the step is the node's displacement relative to the tool,
     ds = (y - y_n) - (d - d_n), measured in the current tangent plane: dg_a = t_a . ds.
   * The tangential "pressure" t_T (local components on t1, t2) is the elastic predictor
     t_T^e = t_T^n + K_T dg_T, returned radially to the cone |t_T| <= mu t_N.
   * The force on the node is f = t_N n - t_Ta t_a (friction opposes the slip); the residual
     R = f_int - f_ext receives -f. */
#ifndef ATRITO_CONTACT_LAW_H
#define ATRITO_CONTACT_LAW_H

typedef struct {
  double KN, KT, mu;
  double delta; /* > 0: the normal bracket smoothed over gaps -delta..delta (-contact_gap_smoothing) */
  double reg;   /* > 0: the normal bracket regularised over a band of penetrations (-contact_regularization):
                   with x = lN + K_N p and b = K_N reg, a = CONTACT_REG_GAP b,
                   t_N = (x + a)^2 / (2 (a + b)) for -a < x < b, x - (b - a)/2 beyond, 0 below -a
                   (C1; no force at gaps beyond CONTACT_REG_GAP reg, slope a/(a+b) at x = 0) */
} ContactLaw;

/* the regularisation's reach on the open side, as a fraction of its width (ContactLaw.reg) */
#define CONTACT_REG_GAP 0.1

#define CONTACT_OPEN  0
#define CONTACT_STICK 1
#define CONTACT_SLIP  2

/* Local frame (eqs 28-30): t2 = n x s / |n x s|, t1 = t2 x n, with s the seed (the chord at
   first contact, the t1 of the previous iteration afterwards). Returns 0, or 1 when s is
   (numerically) parallel to n. */
int ContactFrame(const double n[3], const double s[3], double t1[3], double t2[3]);

/* The frame carried from the normal n0 (of the previous iterate, or of the committed state) to
   the normal n: r = R s with R the rotation about n0 x n that takes n0 to n (Rodrigues:
   r = c s + k x s + k (k . s)/(1 + c), k = n0 x n, c = n0 . n). The tangential multipliers are
   components on the frame; R carries t1 and t2 alike, so the traction they stand for is carried
   whatever the frame's orientation in the plane. The projection of t1 on the new plane alone (eq 30
   with the previous t1 as seed) turns the frame by an angle of second order in the normal's turn
   that depends on that orientation: the carried traction then depended on the arbitrary frame (the
   chord at a sphere's pole), and a symmetric problem lost its symmetry. Returns 0, or 1 (r = s, the
   projection is left to ContactFrame) when n0 is zero (unknown) or turned by more than 120 degrees. */
int ContactFrameCarry(const double n0[3], const double n[3], const double s[3], double r[3]);

/* Return map of the tangential pressure (eqs 14-18). Inputs: committed local components tTn,
   local slip increment dg, normal pressure tN >= 0. Output tT, and the status (stick/slip).
   When Y is not NULL, the consistent tangent d tT / d(dg_1, dg_2, penetration) (2x3, row-major),
   i.e. the first two rows of eq 23 (the third row is (0, 0, K_N)). */
int ContactReturnMap(const ContactLaw *law, const double tTn[2], const double dg[2], double tN, double tT[2], double *Y);

/* Everything a node contributes at the current iterate.
   In:  law; gap g; normal n; dn = d n / d y (3x3, row-major; NULL for a flat tool); frame seed s;
        committed tangential pressure tTn (zero if the node was not in contact); slip increment ds.
   Out: residual contribution R[3] (= -f), tangent K = dR/dy (3x3, may be NULL), the frame t1,
        the pressures tN and tT[2], and the status. An open node (g > 0) contributes nothing; a touching
   node (g = 0) is active with zero force and full stiffness. */
int ContactNodeEval(const ContactLaw *law, double g, const double n[3], const double *dn, const double s[3], const double tTn[2], const double ds[3], double R[3], double *K, double t1[3], double *tN, double tT[2]);

/* The same with a normal multiplier lN >= 0 (augmented Lagrangian, held fixed within a Newton
   solve): t_N = lN + K_N (-g), active when g <= 0 or t_N > 0 (a node held by its multiplier may
   stand off the tool by up to lN/K_N); the tangential multiplier is passed as tTn (the predictor is
   t_T^e = tTn + K_T dg_T). With lN = 0 it is ContactNodeEval bit for bit. */
int ContactNodeEvalAug(const ContactLaw *law, double lN, double g, const double n[3], const double *dn, const double s[3], const double tTn[2], const double ds[3], double R[3], double *K, double t1[3], double *tN, double tT[2]);

/* Tributary areas of the corners of a 4-node face (corners in cyclic order): a_i = integral over
   the bilinear face of N_i dA (2x2 Gauss; exact for a plane face). They sum to the face area. */
void ContactQuadAreas(const double x[4][3], double a[4]);

#endif
