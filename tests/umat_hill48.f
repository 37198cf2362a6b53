C     Hill 1948 anisotropic elasto-plasticity as an Abaqus/Standard
C     UMAT, finite strains (NLGEOM), solid elements: NDI = NSHR = 3,
C     order 11, 22, 33, 12, 13, 23, engineering shear strains. The
C     counterpart of the built-in material type hill48 (doc/umat.md).
C
C     STRESS arrives as the Cauchy stress at the start of the increment,
C     already rotated by the incremental rotation DROT; DSTRAN is the
C     logarithmic strain increment in the same frame. The update acts on
C     the Kirchhoff stress tau = J sigma (J from DFGRD0, DFGRD1):
C       tau_tr = J0 sigma_in + lambda tr(de) 1 + 2G de
C     then a return map in the orthotropy frame Q (columns: rolling,
C     transverse, normal direction in the current configuration), in
C     Mandel notation s = (11, 22, 33, 23, 31, 12), shears times sqrt 2:
C       q(s)^2 = s^T P s,  P = [G+H -H -G; -H F+H -F; -G -F F+G],
C                          P44 = L, P55 = M, P66 = N
C       s = s_tr - 2G lam P s,  i.e. s = (I + 2G lam P)^{-1} s_tr
C       (P annihilates the hydrostatic part, the elasticity is
C       isotropic), ep = ep_n + lam q(s), q(s) = sigma_y(ep):
C     one scalar equation r(lam) = q(lam) - sigma_y(ep_n + lam q(lam)),
C     solved by Newton's method from lam = 0 in a bracket; sigma =
C     tau / J1.
C
C     The orthotropy frame: Q = A0 in the reference configuration
C     (rolling direction rd, transverse nd x rd, normal nd), rotated by
C       IAX = 0: the rotation R of the polar decomposition of DFGRD1
C                (as the built-in hill48: the frame of F = R U);
C       IAX = 1: the product of the incremental rotations DROT (those
C                applied to STRESS), kept in STATEV(8..16).
C     With IAX = 1 the update is objective in the sense of doc/umat.md
C     (rotating STRESS, DSTRAN and the frame rotates the result), so the
C     tangent d tau/dF of the bridge is exact; with IAX = 0 it misses
C     the derivative of the frame (doc/umat.md, "Hill 48 UMAT").
C
C     DDSDDE = (1/J1) d tau / d DSTRAN: the Jacobian of the Jaumann rate
C     of Kirchhoff stress over J, the consistent tangent of the return
C     (in the frame Q, Mandel; rotated to the global basis):
C       D_alg = Xi D + v w^T,  Xi = (I + 2G lam P)^{-1},
C       v = d s/d lam = -2G q Xi m,  m = P s / q,
C       w = -(1 - H' lam) D Xi m / (dr/dlam),
C       dr/dlam = -q (2G m^T Xi m + H' (1 - 2G lam m^T Xi m)).
C
C     PROPS (NPROPS = 13, 14 or 20):
C       1 E, 2 nu,
C       3 IHARD: 0 linear, sigma_y = PROPS(4) + PROPS(5) ep;
C                1 Swift,  sigma_y = PROPS(4) (PROPS(5) + ep)^PROPS(6)
C       7 IANI:  0 r-values r0, r45, r90 = PROPS(8..10) (PROPS(11..13)
C                unused), with the plane-stress relations of hill48.c
C                (G + H = 1, L = M = 3/2);
C                1 coefficients F, G, H, L, M, N = PROPS(8..13)
C      14 IAX (above; default 0)
C      15-17 rolling direction, 18-20 sheet normal in the reference
C                configuration (default x and z)
C     STATEV(1): equivalent plastic strain (work-equivalent);
C     STATEV(2..7): plastic strain 11, 22, 33, 12, 13, 23 (engineering
C       shears), global basis, rotated with DROT as STRAN;
C     STATEV(8..16): with IAX = 1, the frame Q (column-major; zero in the
C       virgin material means A0). NSTATV >= 7 (IAX = 0) or 16 (IAX = 1).
C     Invalid PROPS or NSTATV: STRESS = NaN (the caller's error for a
C     failed update). PNEWDT = 0.5 when the return map does not converge.
      SUBROUTINE UMAT(STRESS,STATEV,DDSDDE,SSE,SPD,SCD,
     1 RPL,DDSDDT,DRPLDE,DRPLDT,
     2 STRAN,DSTRAN,TIME,DTIME,TEMP,DTEMP,PREDEF,DPRED,CMNAME,
     3 NDI,NSHR,NTENS,NSTATV,PROPS,NPROPS,COORDS,DROT,PNEWDT,
     4 CELENT,DFGRD0,DFGRD1,NOEL,NPT,LAYER,KSPT,KSTEP,KINC)
      IMPLICIT NONE
      CHARACTER*80 CMNAME
      INTEGER NDI,NSHR,NTENS,NSTATV,NPROPS,NOEL,NPT,LAYER,KSPT,
     1 KSTEP,KINC
      DOUBLE PRECISION STRESS(NTENS),STATEV(NSTATV),
     1 DDSDDE(NTENS,NTENS),DDSDDT(NTENS),DRPLDE(NTENS),
     2 STRAN(NTENS),DSTRAN(NTENS),TIME(2),PREDEF(1),DPRED(1),
     3 PROPS(NPROPS),COORDS(3),DROT(3,3),DFGRD0(3,3),DFGRD1(3,3)
      DOUBLE PRECISION SSE,SPD,SCD,RPL,DRPLDT,DTIME,TEMP,DTEMP,
     1 PNEWDT,CELENT
C
      DOUBLE PRECISION E,XNU,BK,G,XLM,C2G,J0,J1,HDET
      DOUBLE PRECISION HP(6),HCF,HCG,HCH,HCL,HCM,HCN,R0,R45,R90
      DOUBLE PRECISION A0(3,3),Q(3,3),QN(3,3),RP(3,3)
      DOUBLE PRECISION TG(3,3),TL(3,3),WK(3,3),EPT(3,3)
      DOUBLE PRECISION P(6,6),XI(6,6),DM(6,6),DA(6,6)
      DOUBLE PRECISION STR(6),S(6),PS(6),XM(6),XIM(6),V(6),W(6),EV(6)
      DOUBLE PRECISION EP,DL,QTR,QQ,SY,HS,R,DR,LO,HI,DLN,QP,XMXM,TR,T
      DOUBLE PRECISION XNAN
      INTEGER IHARD,IANI,IAX,I,J,K,IT,IPL
C     Abaqus component I is Mandel component IAB(I); stress = Mandel *
C     SAB, Mandel = engineering strain * SAB
      INTEGER IAB(6)
      DOUBLE PRECISION SAB(6)
      DATA IAB /1, 2, 3, 6, 5, 4/
      DATA SAB /1.D0, 1.D0, 1.D0, 0.70710678118654752D0,
     1 0.70710678118654752D0, 0.70710678118654752D0/
C
      XNAN = 0.D0
      XNAN = XNAN / XNAN
      IF (NTENS.NE.6 .OR. NPROPS.LT.13 .OR. NSTATV.LT.7) GO TO 90
      E = PROPS(1)
      XNU = PROPS(2)
      IHARD = NINT(PROPS(3))
      IANI = NINT(PROPS(7))
      IAX = 0
      IF (NPROPS.GE.14) IAX = NINT(PROPS(14))
      IF (.NOT.(E.GT.0.D0 .AND. XNU.GT.-1.D0 .AND. XNU.LT.0.5D0))
     1  GO TO 90
      IF (IHARD.LT.0 .OR. IHARD.GT.1 .OR. IANI.LT.0 .OR. IANI.GT.1)
     1  GO TO 90
      IF (IAX.LT.0 .OR. IAX.GT.1) GO TO 90
      IF (IAX.EQ.1 .AND. NSTATV.LT.16) GO TO 90
      DO I = 1, 3
        HP(I) = PROPS(3 + I)
      END DO
      IF (IANI.EQ.0) THEN
        R0 = PROPS(8)
        R45 = PROPS(9)
        R90 = PROPS(10)
        IF (.NOT.(R0.GT.0.D0 .AND. R45.GT.0.D0 .AND. R90.GT.0.D0))
     1    GO TO 90
        HCH = R0 / (1.D0 + R0)
        HCG = 1.D0 / (1.D0 + R0)
        HCF = R0 / (R90 * (1.D0 + R0))
        HCN = (R0 + R90) * (1.D0 + 2.D0 * R45)
     1      / (2.D0 * R90 * (1.D0 + R0))
        HCL = 1.5D0
        HCM = 1.5D0
      ELSE
        HCF = PROPS(8)
        HCG = PROPS(9)
        HCH = PROPS(10)
        HCL = PROPS(11)
        HCM = PROPS(12)
        HCN = PROPS(13)
      END IF
      IF (.NOT.(HCF+HCG+HCH.GT.0.D0 .AND.
     1  HCF*HCG+HCG*HCH+HCH*HCF.GT.0.D0 .AND. HCL.GT.0.D0 .AND.
     2  HCM.GT.0.D0 .AND. HCN.GT.0.D0)) GO TO 90
C     the frame in the reference configuration
      CALL HFRAME(NPROPS, PROPS, A0, I)
      IF (I.NE.0) GO TO 90
C
      BK = E / (3.D0 * (1.D0 - 2.D0 * XNU))
      G = E / (2.D0 * (1.D0 + XNU))
      XLM = BK - 2.D0 * G / 3.D0
      C2G = 2.D0 * G
      J0 = HDET(DFGRD0)
      J1 = HDET(DFGRD1)
      EP = STATEV(1)
C
C     the current frame Q
      IF (IAX.EQ.0) THEN
        CALL HPOLAR(DFGRD1, RP)
        CALL HMUL(RP, A0, Q)
      ELSE
        T = 0.D0
        DO I = 1, 9
          T = T + ABS(STATEV(7 + I))
        END DO
        DO J = 1, 3
          DO I = 1, 3
            IF (T.GT.0.D0) THEN
              QN(I, J) = STATEV(7 + I + 3 * (J - 1))
            ELSE
              QN(I, J) = A0(I, J)
            END IF
          END DO
        END DO
        CALL HMUL(DROT, QN, Q)
        DO J = 1, 3
          DO I = 1, 3
            STATEV(7 + I + 3 * (J - 1)) = Q(I, J)
          END DO
        END DO
      END IF
C
C     Hill matrix P (Mandel, frame Q) and the elasticity D
      DO J = 1, 6
        DO I = 1, 6
          P(I, J) = 0.D0
          DM(I, J) = 0.D0
        END DO
      END DO
      P(1, 1) = HCG + HCH
      P(1, 2) = -HCH
      P(1, 3) = -HCG
      P(2, 2) = HCF + HCH
      P(2, 3) = -HCF
      P(3, 3) = HCF + HCG
      P(2, 1) = P(1, 2)
      P(3, 1) = P(1, 3)
      P(3, 2) = P(2, 3)
      P(4, 4) = HCL
      P(5, 5) = HCM
      P(6, 6) = HCN
      DO I = 1, 6
        DM(I, I) = C2G
      END DO
      DO J = 1, 3
        DO I = 1, 3
          DM(I, J) = DM(I, J) + XLM
        END DO
      END DO
C
C     trial Kirchhoff stress (global), in the frame Q (Mandel)
      TR = DSTRAN(1) + DSTRAN(2) + DSTRAN(3)
      CALL HV2T(STRESS, TG, 1.D0)
      CALL HV2T(DSTRAN, WK, 0.5D0)
      DO J = 1, 3
        DO I = 1, 3
          TG(I, J) = J0 * TG(I, J) + C2G * WK(I, J)
        END DO
        TG(J, J) = TG(J, J) + XLM * TR
      END DO
      CALL HROT(Q, TG, TL, 1)
      CALL HT2M(TL, STR)
      CALL HMV6(P, STR, PS)
      QTR = 0.D0
      DO I = 1, 6
        QTR = QTR + STR(I) * PS(I)
      END DO
      QTR = SQRT(MAX(QTR, 0.D0))
      CALL HYIELD(IHARD, HP, EP, SY, HS)
C
      DL = 0.D0
      IPL = 0
      DO I = 1, 6
        S(I) = STR(I)
      END DO
      IF (QTR - SY .GT. 0.D0) THEN
        IPL = 1
        LO = 0.D0
        HI = -1.D0
        DO IT = 1, 100
          CALL HXI(P, C2G * DL, XI)
          CALL HMV6(XI, STR, S)
          CALL HMV6(P, S, PS)
          QQ = 0.D0
          DO I = 1, 6
            QQ = QQ + S(I) * PS(I)
          END DO
          QQ = SQRT(MAX(QQ, 0.D0))
          CALL HYIELD(IHARD, HP, EP + DL * QQ, SY, HS)
          R = QQ - SY
          IF (ABS(R) .LE. 1.D-12 * QTR) GO TO 10
          IF (R .GT. 0.D0) THEN
            LO = DL
          ELSE
            HI = DL
          END IF
          CALL HMV6(XI, PS, XIM)
          XMXM = 0.D0
          DO I = 1, 6
            XMXM = XMXM + PS(I) * XIM(I)
          END DO
          QP = -C2G * XMXM / QQ
          DR = QP - HS * (QQ + DL * QP)
          IF (.NOT. (DR .LT. 0.D0)) GO TO 80
          DLN = DL - R / DR
          IF (HI .GE. 0.D0 .AND. .NOT. (DLN .GT. LO .AND. DLN .LT. HI))
     1      DLN = 0.5D0 * (LO + HI)
          IF (.NOT. (DLN .GT. 0.D0)) GO TO 80
C         stalled at round-off: converged as far as it can be
          IF (ABS(DLN - DL) .LE. 4.D-16 * DLN) GO TO 10
          DL = DLN
        END DO
   80   CONTINUE
        PNEWDT = 0.5D0
        RETURN
   10   CONTINUE
      END IF
C
C     stress, state
      CALL HM2T(S, TL)
      CALL HROT(Q, TL, TG, 0)
      STRESS(1) = TG(1, 1) / J1
      STRESS(2) = TG(2, 2) / J1
      STRESS(3) = TG(3, 3) / J1
      STRESS(4) = TG(1, 2) / J1
      STRESS(5) = TG(1, 3) / J1
      STRESS(6) = TG(2, 3) / J1
      CALL HV2T(STATEV(2), EPT, 0.5D0)
      CALL HROT(DROT, EPT, WK, 0)
      IF (IPL.EQ.1) THEN
        STATEV(1) = EP + DL * QQ
        DO I = 1, 6
          EV(I) = DL * PS(I)
        END DO
        CALL HM2T(EV, TL)
        CALL HROT(Q, TL, EPT, 0)
        DO J = 1, 3
          DO I = 1, 3
            WK(I, J) = WK(I, J) + EPT(I, J)
          END DO
        END DO
      END IF
      STATEV(2) = WK(1, 1)
      STATEV(3) = WK(2, 2)
      STATEV(4) = WK(3, 3)
      STATEV(5) = 2.D0 * WK(1, 2)
      STATEV(6) = 2.D0 * WK(1, 3)
      STATEV(7) = 2.D0 * WK(2, 3)
C
C     the algorithmic tangent in the frame Q
      IF (IPL.EQ.1) THEN
        DO I = 1, 6
          XM(I) = PS(I) / QQ
        END DO
        CALL HMV6(XI, XM, XIM)
        XMXM = 0.D0
        DO I = 1, 6
          XMXM = XMXM + XM(I) * XIM(I)
        END DO
        DR = -QQ * (C2G * XMXM + HS * (1.D0 - C2G * DL * XMXM))
        DO I = 1, 6
          V(I) = -C2G * QQ * XIM(I)
        END DO
        DO J = 1, 6
          T = 0.D0
          DO I = 1, 6
            T = T + XIM(I) * DM(I, J)
          END DO
          W(J) = -(1.D0 - HS * DL) * T / DR
        END DO
        DO J = 1, 6
          DO I = 1, 6
            T = 0.D0
            DO K = 1, 6
              T = T + XI(I, K) * DM(K, J)
            END DO
            DA(I, J) = T + V(I) * W(J)
          END DO
        END DO
      ELSE
        DO J = 1, 6
          DO I = 1, 6
            DA(I, J) = DM(I, J)
          END DO
        END DO
      END IF
C     DDSDDE = T D_alg T^T / J1 with T the Mandel form of S -> Q S Q^T
C     (orthogonal), in Abaqus's order and shear conventions: stress
C     component 12 = Mandel 6 / sqrt 2, engineering strain 12 = sqrt 2
C     Mandel 6 (the elastic D is isotropic: no rotation)
      IF (IPL.EQ.1) THEN
        DO J = 1, 6
          DO I = 1, 6
            EV(I) = 0.D0
          END DO
          EV(J) = 1.D0
          CALL HM2T(EV, TL)
          CALL HROT(Q, TL, TG, 0)
          CALL HT2M(TG, EV)
          DO I = 1, 6
            XI(I, J) = EV(I)
          END DO
        END DO
        DO J = 1, 6
          DO I = 1, 6
            T = 0.D0
            DO K = 1, 6
              T = T + XI(I, K) * DA(K, J)
            END DO
            DM(I, J) = T
          END DO
        END DO
        DO J = 1, 6
          DO I = 1, 6
            T = 0.D0
            DO K = 1, 6
              T = T + DM(I, K) * XI(J, K)
            END DO
            DA(I, J) = T
          END DO
        END DO
      END IF
      DO K = 1, 6
        DO I = 1, 6
          DDSDDE(I, K) = DA(IAB(I), IAB(K)) * SAB(I) * SAB(K) / J1
        END DO
      END DO
      RETURN
C
   90 CONTINUE
      DO I = 1, NTENS
        STRESS(I) = XNAN
      END DO
      RETURN
      END
C
C     yield stress and its slope: IHARD 0 linear HP(1) + HP(2) ep,
C     1 Swift HP(1) (HP(2) + ep)^HP(3)
      SUBROUTINE HYIELD(IHARD, HP, EP, SY, HS)
      IMPLICIT NONE
      INTEGER IHARD
      DOUBLE PRECISION HP(3), EP, SY, HS
      IF (IHARD .EQ. 1) THEN
        SY = HP(1) * (HP(2) + EP)**HP(3)
        HS = HP(3) * SY / (HP(2) + EP)
      ELSE
        SY = HP(1) + HP(2) * EP
        HS = HP(2)
      END IF
      RETURN
      END
C
C     the reference frame A0 = [rd, nd x rd, nd] from PROPS(15..20)
C     (default x, z); IERR = 1 for zero or non-orthogonal vectors
      SUBROUTINE HFRAME(NPROPS, PROPS, A0, IERR)
      IMPLICIT NONE
      INTEGER NPROPS, IERR, I
      DOUBLE PRECISION PROPS(NPROPS), A0(3,3), RD(3), ND(3), TD(3)
      DOUBLE PRECISION LR, LN, C
      IERR = 0
      DO I = 1, 3
        RD(I) = 0.D0
        ND(I) = 0.D0
      END DO
      RD(1) = 1.D0
      ND(3) = 1.D0
      IF (NPROPS .GE. 20) THEN
        DO I = 1, 3
          RD(I) = PROPS(14 + I)
          ND(I) = PROPS(17 + I)
        END DO
      ELSE IF (NPROPS .GT. 14) THEN
        IERR = 1
        RETURN
      END IF
      LR = SQRT(RD(1)**2 + RD(2)**2 + RD(3)**2)
      LN = SQRT(ND(1)**2 + ND(2)**2 + ND(3)**2)
      IF (.NOT. (LR .GT. 0.D0 .AND. LN .GT. 0.D0)) THEN
        IERR = 1
        RETURN
      END IF
      C = 0.D0
      DO I = 1, 3
        RD(I) = RD(I) / LR
        ND(I) = ND(I) / LN
        C = C + RD(I) * ND(I)
      END DO
      IF (ABS(C) .GT. 1.D-6) THEN
        IERR = 1
        RETURN
      END IF
      DO I = 1, 3
        RD(I) = RD(I) - C * ND(I)
      END DO
      LR = SQRT(RD(1)**2 + RD(2)**2 + RD(3)**2)
      DO I = 1, 3
        RD(I) = RD(I) / LR
      END DO
      TD(1) = ND(2) * RD(3) - ND(3) * RD(2)
      TD(2) = ND(3) * RD(1) - ND(1) * RD(3)
      TD(3) = ND(1) * RD(2) - ND(2) * RD(1)
      DO I = 1, 3
        A0(I, 1) = RD(I)
        A0(I, 2) = TD(I)
        A0(I, 3) = ND(I)
      END DO
      RETURN
      END
C
C     Xi = (I + c P)^{-1}: the normal block by its adjugate, the shear
C     block diagonal
      SUBROUTINE HXI(P, C, XI)
      IMPLICIT NONE
      DOUBLE PRECISION P(6,6), C, XI(6,6), A(3,3), B(3,3), D
      INTEGER I, J
      DO J = 1, 6
        DO I = 1, 6
          XI(I, J) = 0.D0
        END DO
      END DO
      DO J = 1, 3
        DO I = 1, 3
          A(I, J) = C * P(I, J)
        END DO
        A(J, J) = A(J, J) + 1.D0
      END DO
      B(1,1) = A(2,2) * A(3,3) - A(2,3) * A(3,2)
      B(1,2) = A(1,3) * A(3,2) - A(1,2) * A(3,3)
      B(1,3) = A(1,2) * A(2,3) - A(1,3) * A(2,2)
      B(2,1) = A(2,3) * A(3,1) - A(2,1) * A(3,3)
      B(2,2) = A(1,1) * A(3,3) - A(1,3) * A(3,1)
      B(2,3) = A(1,3) * A(2,1) - A(1,1) * A(2,3)
      B(3,1) = A(2,1) * A(3,2) - A(2,2) * A(3,1)
      B(3,2) = A(1,2) * A(3,1) - A(1,1) * A(3,2)
      B(3,3) = A(1,1) * A(2,2) - A(1,2) * A(2,1)
      D = A(1,1) * B(1,1) + A(1,2) * B(2,1) + A(1,3) * B(3,1)
      DO J = 1, 3
        DO I = 1, 3
          XI(I, J) = B(I, J) / D
        END DO
        XI(J + 3, J + 3) = 1.D0 / (1.D0 + C * P(J + 3, J + 3))
      END DO
      RETURN
      END
C
C     y = M x (6 x 6)
      SUBROUTINE HMV6(M, X, Y)
      IMPLICIT NONE
      DOUBLE PRECISION M(6,6), X(6), Y(6)
      INTEGER I, J
      DO I = 1, 6
        Y(I) = 0.D0
        DO J = 1, 6
          Y(I) = Y(I) + M(I, J) * X(J)
        END DO
      END DO
      RETURN
      END
C
C     C = A B (3 x 3)
      SUBROUTINE HMUL(A, B, C)
      IMPLICIT NONE
      DOUBLE PRECISION A(3,3), B(3,3), C(3,3)
      INTEGER I, J, K
      DO J = 1, 3
        DO I = 1, 3
          C(I, J) = 0.D0
          DO K = 1, 3
            C(I, J) = C(I, J) + A(I, K) * B(K, J)
          END DO
        END DO
      END DO
      RETURN
      END
C
C     ITR = 0: B = Q A Q^T;  ITR = 1: B = Q^T A Q  (A symmetric)
      SUBROUTINE HROT(Q, A, B, ITR)
      IMPLICIT NONE
      INTEGER ITR, I, J
      DOUBLE PRECISION Q(3,3), A(3,3), B(3,3), W(3,3), T
      IF (ITR .EQ. 0) THEN
C       W = A Q^T, B = Q W
        DO J = 1, 3
          DO I = 1, 3
            W(I, J) = A(I, 1) * Q(J, 1) + A(I, 2) * Q(J, 2)
     1              + A(I, 3) * Q(J, 3)
          END DO
        END DO
        DO J = 1, 3
          DO I = J, 3
            T = Q(I, 1) * W(1, J) + Q(I, 2) * W(2, J)
     1        + Q(I, 3) * W(3, J)
            B(I, J) = T
            B(J, I) = T
          END DO
        END DO
      ELSE
C       W = A Q, B = Q^T W
        DO J = 1, 3
          DO I = 1, 3
            W(I, J) = A(I, 1) * Q(1, J) + A(I, 2) * Q(2, J)
     1              + A(I, 3) * Q(3, J)
          END DO
        END DO
        DO J = 1, 3
          DO I = J, 3
            T = Q(1, I) * W(1, J) + Q(2, I) * W(2, J)
     1        + Q(3, I) * W(3, J)
            B(I, J) = T
            B(J, I) = T
          END DO
        END DO
      END IF
      RETURN
      END
C
C     Abaqus vector (11, 22, 33, 12, 13, 23) to a symmetric tensor, the
C     shears times F (1 for stresses, 1/2 for engineering strains)
      SUBROUTINE HV2T(V, T, F)
      IMPLICIT NONE
      DOUBLE PRECISION V(6), T(3,3), F
      T(1,1) = V(1)
      T(2,2) = V(2)
      T(3,3) = V(3)
      T(1,2) = F * V(4)
      T(2,1) = T(1,2)
      T(1,3) = F * V(5)
      T(3,1) = T(1,3)
      T(2,3) = F * V(6)
      T(3,2) = T(2,3)
      RETURN
      END
C
C     symmetric tensor <-> Mandel vector (11, 22, 33, 23, 31, 12)
      SUBROUTINE HT2M(T, V)
      IMPLICIT NONE
      DOUBLE PRECISION T(3,3), V(6), SQ2
      PARAMETER (SQ2 = 1.41421356237309504880D0)
      V(1) = T(1,1)
      V(2) = T(2,2)
      V(3) = T(3,3)
      V(4) = SQ2 * T(2,3)
      V(5) = SQ2 * T(3,1)
      V(6) = SQ2 * T(1,2)
      RETURN
      END
C
      SUBROUTINE HM2T(V, T)
      IMPLICIT NONE
      DOUBLE PRECISION T(3,3), V(6), SQ2
      PARAMETER (SQ2 = 1.41421356237309504880D0)
      T(1,1) = V(1)
      T(2,2) = V(2)
      T(3,3) = V(3)
      T(2,3) = V(4) / SQ2
      T(3,2) = T(2,3)
      T(3,1) = V(5) / SQ2
      T(1,3) = T(3,1)
      T(1,2) = V(6) / SQ2
      T(2,1) = T(1,2)
      RETURN
      END
C
C     the rotation R of the polar decomposition F = R U: U^2 = F^T F by
C     Jacobi's method, R = F U^{-1}
      SUBROUTINE HPOLAR(F, R)
      IMPLICIT NONE
      DOUBLE PRECISION F(3,3), R(3,3), C(3,3), D(3), V(3,3), UI(3,3)
      INTEGER I, J, K
      DO J = 1, 3
        DO I = 1, 3
          C(I, J) = 0.D0
          DO K = 1, 3
            C(I, J) = C(I, J) + F(K, I) * F(K, J)
          END DO
        END DO
      END DO
      CALL HJACOB(C, D, V)
      DO I = 1, 3
        D(I) = 1.D0 / SQRT(D(I))
      END DO
      DO J = 1, 3
        DO I = 1, 3
          UI(I, J) = 0.D0
          DO K = 1, 3
            UI(I, J) = UI(I, J) + V(I, K) * D(K) * V(J, K)
          END DO
        END DO
      END DO
      CALL HMUL(F, UI, R)
      RETURN
      END
C
C     eigenvalues D and eigenvectors V (columns) of a symmetric 3 x 3 A:
C     cyclic Jacobi rotations until the off-diagonal part is below
C     1e-15 of the norm (A is overwritten)
      SUBROUTINE HJACOB(A, D, V)
      IMPLICIT NONE
      DOUBLE PRECISION A(3,3), D(3), V(3,3), TH, T, C, S, OFF, DN
      DOUBLE PRECISION AKP, AKQ, APP, AQQ, APQ
      INTEGER I, J, K, IP, IQ, ISW, IPQ
      DO J = 1, 3
        DO I = 1, 3
          V(I, J) = 0.D0
        END DO
        V(J, J) = 1.D0
      END DO
      DO ISW = 1, 50
        OFF = A(1,2)**2 + A(1,3)**2 + A(2,3)**2
        DN = A(1,1)**2 + A(2,2)**2 + A(3,3)**2
        IF (OFF .LE. 1.D-30 * DN) GO TO 20
        DO IPQ = 1, 3
          IF (IPQ .EQ. 1) THEN
            IP = 1
            IQ = 2
          ELSE IF (IPQ .EQ. 2) THEN
            IP = 1
            IQ = 3
          ELSE
            IP = 2
            IQ = 3
          END IF
          APQ = A(IP, IQ)
          IF (APQ .NE. 0.D0) THEN
            APP = A(IP, IP)
            AQQ = A(IQ, IQ)
            TH = (AQQ - APP) / (2.D0 * APQ)
            IF (ABS(TH) .GT. 1.D100) THEN
              T = 0.5D0 / TH
            ELSE
              T = SIGN(1.D0, TH) / (ABS(TH) + SQRT(TH * TH + 1.D0))
            END IF
            C = 1.D0 / SQRT(T * T + 1.D0)
            S = T * C
            A(IP, IP) = APP - T * APQ
            A(IQ, IQ) = AQQ + T * APQ
            A(IP, IQ) = 0.D0
            A(IQ, IP) = 0.D0
            DO K = 1, 3
              IF (K .NE. IP .AND. K .NE. IQ) THEN
                AKP = A(K, IP)
                AKQ = A(K, IQ)
                A(K, IP) = C * AKP - S * AKQ
                A(IP, K) = A(K, IP)
                A(K, IQ) = S * AKP + C * AKQ
                A(IQ, K) = A(K, IQ)
              END IF
            END DO
            DO K = 1, 3
              AKP = V(K, IP)
              AKQ = V(K, IQ)
              V(K, IP) = C * AKP - S * AKQ
              V(K, IQ) = S * AKP + C * AKQ
            END DO
          END IF
        END DO
      END DO
   20 CONTINUE
      DO I = 1, 3
        D(I) = A(I, I)
      END DO
      RETURN
      END
C
      DOUBLE PRECISION FUNCTION HDET(A)
      IMPLICIT NONE
      DOUBLE PRECISION A(3,3)
      HDET = A(1,1) * (A(2,2) * A(3,3) - A(2,3) * A(3,2))
     1     - A(1,2) * (A(2,1) * A(3,3) - A(2,3) * A(3,1))
     2     + A(1,3) * (A(2,1) * A(3,2) - A(2,2) * A(3,1))
      RETURN
      END
