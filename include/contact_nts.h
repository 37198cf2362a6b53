/* Node-to-surface kinematics against a deformable master face: closest-point projection of a
   slave node on a bilinear quadrilateral (nen = 4) or linear triangle (nen = 3), the gap and
   normal there, their exact first derivatives with respect to all the nodes involved, and the
   relative slip increment between two deformable surfaces. Plain arrays, no PETSc.

   Conventions:
   * Quad: corners in cyclic order at (xi_a, eta_a) = (-1,-1), (1,-1), (1,1), (-1,1),
     N_a = (1 + xi_a xi)(1 + eta_a eta)/4, inside for (xi, eta) in [-1, 1]^2.
     Triangle: N = (1 - xi - eta, xi, eta), inside for xi, eta >= 0, xi + eta <= 1.
   * x(xi) = sum_a N_a x_a, a_alpha = x_{,alpha} = sum_a N_a,alpha x_a, m = a_1 x a_2,
     n = m/|m|: corners counter-clockwise seen from outside give n out of the master body.
   * g = (x_s - x).n at the projection, negative when the slave node has penetrated.
   * Unknowns X = (x_s, x_1, ..., x_nen): ncomp = 3 + 3 nen columns, column 3 k + i is
     component i of node k (k = 0 the slave, k = a + 1 the master corner a, a = 0..nen-1).
     Derivative arrays are row-major with row stride ncomp. */
#ifndef ATRITO_CONTACT_NTS_H
#define ATRITO_CONTACT_NTS_H

#define NTS_MAXCOMP 15

typedef struct {
  int    nen;                         /* 3 or 4 */
  int    ncomp;                       /* 3 + 3 nen, the columns of the derivatives */
  int    inside;                      /* the projection lies in the face (widened by tol) */
  double xi[2];                       /* parameters of the projection (not clamped to the face) */
  double N[4], dN[4][2];              /* N_a and N_a,alpha at xi */
  double x[3];                        /* the closest point x(xi) */
  double a[2][3];                     /* tangents a_alpha at xi */
  double g;                           /* gap (x_s - x).n */
  double n[3];                        /* unit outward normal of the face at xi */
  double dxi[2 * NTS_MAXCOMP];        /* d xi / dX, 2 x ncomp */
  double dg[NTS_MAXCOMP];             /* d g / dX, 1 x ncomp */
  double dn[3 * NTS_MAXCOMP];         /* d n / dX, 3 x ncomp */
} NTSProjection;

/* Closest-point projection of xs on the face xm[nen] (its bilinear or planar extension): Newton
   on r_alpha(xi) = (x_s - x(xi)).a_alpha(xi) = 0 with the exact Jacobian
   dr_alpha/dxi_beta = -a_alpha.a_beta + (x_s - x).a_{alpha,beta}, safeguarded as a descent on the
   distance (Gauss-Newton steps where the distance's Hessian is not positive definite, steps cut to
   length 1 in parameter units and halved until the distance decreases), at most 30 iterations.
   In:  nen (3 or 4); slave position xs; corners xm[nen]; start xi0 (NULL: the centroid);
        tol, the widening of the face for the inside flag (quad: |xi|, |eta| <= 1 + tol;
        triangle: xi, eta >= -tol, xi + eta <= 1 + tol); derivs: nonzero to fill dxi, dg, dn.
   Out: *p. Returns 0 when converged; 1 for a degenerate face (|a_1 x a_2| ~ 0 at an iterate) or a
        singular Jacobian at the solution; 2 when not converged; -1 for a bad nen.
        On failure p holds the last iterate's xi, N, dN, x, a (finite for finite input) and zeros
        elsewhere (inside = 0). The point found is a stationary point of the distance, in practice
        a local minimum on the extension (not necessarily the global one, nor on the face). */
int NTSProject(int nen, const double xs[3], const double xm[][3], const double xi0[2], double tol, int derivs, NTSProjection *p);

/* Projection along the normal field interpolated from corner normals nbar[nen] (unit or not; the
   smoothed master surface's: each the mean of the faces' normals around the corner): the point
   x(xi) of the face and the gap g with x_s = x(xi) + g n(xi), n = s/|s|, s = sum_a N_a nbar_a.
   Newton on (xi, g) from xi0 (NULL: the centroid). The corner normals are held fixed in the
   derivatives (dxi, dg, dn with respect to X = (x_s, x_1..x_nen) only). The map is continuous
   across two faces that share an edge and its corner normals. Returns as NTSProject; p->a holds
   the face's tangents, p->n the field's normal. */
int NTSProjectNormal(int nen, const double xs[3], const double xm[][3], const double nbar[][3], const double xi0[2], double tol, int derivs, NTSProjection *p);

/* Slip increment of the slave relative to the master's material point now under it:
   ds = (x_s - x_s0) - sum_a N_a(xi) (x_a - x_a0), and when dds is not NULL (then p must come
   from NTSProject with derivs) d(ds)/dX = [I, -N_1 I, ..., -N_nen I]
   - sum_a (x_a - x_a0) (N_a,beta dxi_beta/dX), 3 x ncomp row-major.
   In:  p (the projection of xs on xm); current xs, xm[nen]; committed xs0, xm0[nen].
   Out: ds[3]; dds (3 x ncomp) or NULL. */
void NTSSlip(const NTSProjection *p, const double xs[3], const double xs0[3], const double xm[][3], const double xm0[][3], double ds[3], double *dds);

/* Chord seeding the local frame (eq 28): t = x(xi + 0.01, eta) - x(xi, eta) on the face xm at the
   projection p. */
void NTSChord(const NTSProjection *p, const double xm[][3], double t[3]);

#endif
