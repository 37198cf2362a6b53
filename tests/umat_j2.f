C     Isotropic J2 elasto-plasticity as an Abaqus/Standard UMAT, finite
C     strains (NLGEOM), solid elements: NDI = NSHR = 3, order 11, 22,
C     33, 12, 13, 23, engineering shear strains.
C
C     STRESS arrives as the Cauchy stress at the start of the increment,
C     already rotated by the incremental rotation; DSTRAN is the
C     logarithmic strain increment in the same frame. The return acts
C     on the Kirchhoff stress tau = J sigma (J from DFGRD0, DFGRD1):
C       tau_tr = J0 sigma_in + K tr(de) 1 + 2G dev(de)
C     radial return on the von Mises stress of tau_tr, then
C       sigma = tau / J1.
C     For proportional loading this is the Hencky / log-strain J2 model
C     exactly; otherwise the additive corotational update of the
C     elastic strain differs from the exponential map at second order.
C
C     DDSDDE = (1/J1) d tau / d DSTRAN: the Jacobian of the Jaumann rate
C     of Kirchhoff stress over J, the consistent tangent of the return.
C     Since J1 = J0 exp(tr DSTRAN), it equals d sigma/d DSTRAN + sigma
C     (x) 1.
C
C     PROPS: E, nu, sigma_y0, H           (4 values: linear hardening)
C            E, nu, K, eps0, n            (5 values: Swift hardening,
C                                          sigma_y = K (eps0 + ep)^n)
C     STATEV(1): equivalent plastic strain.
C     PNEWDT = 0.5 when the scalar return does not converge.
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
      DOUBLE PRECISION E,XNU,BK,G,SY0,HM,SWK,SWE,SWN,J0,J1,DETM
      DOUBLE PRECISION T(6),S(6),XN(6),TR,P,Q,EP,DG,LO,HI,SY,HP,R,DN
      DOUBLE PRECISION C1,C2,SNRM
      INTEGER I,K,IT,ISWIFT
C
      IF (NTENS.NE.6) THEN
        PNEWDT = 0.25D0
        RETURN
      END IF
      E = PROPS(1)
      XNU = PROPS(2)
      ISWIFT = 0
      IF (NPROPS.GE.5) ISWIFT = 1
      IF (ISWIFT.EQ.1) THEN
        SWK = PROPS(3)
        SWE = PROPS(4)
        SWN = PROPS(5)
        SY0 = 0.D0
        HM = 0.D0
      ELSE
        SY0 = PROPS(3)
        HM = PROPS(4)
        SWK = 0.D0
        SWE = 0.D0
        SWN = 0.D0
      END IF
      BK = E / (3.D0 * (1.D0 - 2.D0 * XNU))
      G = E / (2.D0 * (1.D0 + XNU))
      J0 = DETM(DFGRD0)
      J1 = DETM(DFGRD1)
      EP = STATEV(1)
C
C     trial Kirchhoff stress
      TR = DSTRAN(1) + DSTRAN(2) + DSTRAN(3)
      DO I = 1, 3
        T(I) = J0 * STRESS(I) + BK * TR
     1       + 2.D0 * G * (DSTRAN(I) - TR / 3.D0)
        T(I + 3) = J0 * STRESS(I + 3) + G * DSTRAN(I + 3)
      END DO
      P = (T(1) + T(2) + T(3)) / 3.D0
      DO I = 1, 3
        S(I) = T(I) - P
        S(I + 3) = T(I + 3)
      END DO
      SNRM = SQRT(S(1)**2 + S(2)**2 + S(3)**2
     1     + 2.D0 * (S(4)**2 + S(5)**2 + S(6)**2))
      Q = SQRT(1.5D0) * SNRM
      CALL YIELDF(ISWIFT, SY0, HM, SWK, SWE, SWN, EP, SY, HP)
C
      DG = 0.D0
      C1 = 1.D0
      C2 = 0.D0
      DO I = 1, 6
        XN(I) = 0.D0
      END DO
      IF (Q - SY .GT. 0.D0) THEN
C       bracketed Newton on r(dg) = q - 3G dg - sigma_y(ep + dg)
        LO = 0.D0
        HI = Q / (3.D0 * G)
        DO IT = 1, 60
          CALL YIELDF(ISWIFT, SY0, HM, SWK, SWE, SWN, EP + DG, SY, HP)
          R = Q - 3.D0 * G * DG - SY
          IF (ABS(R) .LE. 1.D-12 * Q) GO TO 10
          IF (R .GT. 0.D0) THEN
            LO = DG
          ELSE
            HI = DG
          END IF
          DN = DG + R / (3.D0 * G + HP)
          IF (.NOT. (DN .GT. LO .AND. DN .LT. HI)) DN = 0.5D0*(LO+HI)
          DG = DN
        END DO
        PNEWDT = 0.5D0
        RETURN
   10   CONTINUE
        C1 = 1.D0 - 3.D0 * G * DG / Q
        C2 = 6.D0 * G * G * (DG / Q - 1.D0 / (3.D0 * G + HP))
        DO I = 1, 6
          XN(I) = S(I) / SNRM
        END DO
      END IF
C
C     stress and state
      DO I = 1, 3
        STRESS(I) = (P + C1 * S(I)) / J1
        STRESS(I + 3) = C1 * S(I + 3) / J1
      END DO
      STATEV(1) = EP + DG
C
C     DDSDDE = (K 1(x)1 + 2G c1 Idev + c2 n(x)n) / J1
      DO I = 1, 6
        DO K = 1, 6
          DDSDDE(I, K) = C2 * XN(I) * XN(K)
        END DO
      END DO
      DO I = 1, 3
        DO K = 1, 3
          DDSDDE(I, K) = DDSDDE(I, K) + BK - 2.D0 * G * C1 / 3.D0
        END DO
        DDSDDE(I, I) = DDSDDE(I, I) + 2.D0 * G * C1
        DDSDDE(I + 3, I + 3) = DDSDDE(I + 3, I + 3) + G * C1
      END DO
      DO I = 1, 6
        DO K = 1, 6
          DDSDDE(I, K) = DDSDDE(I, K) / J1
        END DO
      END DO
      RETURN
      END
C
C     yield stress and its slope
      SUBROUTINE YIELDF(ISWIFT, SY0, HM, SWK, SWE, SWN, EP, SY, HP)
      IMPLICIT NONE
      INTEGER ISWIFT
      DOUBLE PRECISION SY0, HM, SWK, SWE, SWN, EP, SY, HP
      IF (ISWIFT .EQ. 1) THEN
        SY = SWK * (SWE + EP)**SWN
        HP = SWN * SY / (SWE + EP)
      ELSE
        SY = SY0 + HM * EP
        HP = HM
      END IF
      RETURN
      END
C
      DOUBLE PRECISION FUNCTION DETM(A)
      IMPLICIT NONE
      DOUBLE PRECISION A(3,3)
      DETM = A(1,1) * (A(2,2) * A(3,3) - A(2,3) * A(3,2))
     1     - A(1,2) * (A(2,1) * A(3,3) - A(2,3) * A(3,1))
     2     + A(1,3) * (A(2,1) * A(3,2) - A(2,2) * A(3,1))
      RETURN
      END
