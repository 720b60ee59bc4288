/* The yardstick of bench_pylinkage.py: a four-bar (crank O2-A, coupler A-B with the coupler
 * point C, rocker O4-B) in closed form, one sample after the other, as one would write it by
 * hand in C. Positions, velocities and accelerations of the five points O2, O4, A, B, C at
 * every crank angle, written to out[n][point][p|v|a][x|y].
 *
 * Positions: A on the crank circle; B where the circles (A, |AB|) and (O4, |O4B|) cut, on the
 * side `branch` (+1: left of A->O4); C at coupler coordinates (u along AB, w to its left).
 * Rates: the loop closure vA + w3 x (B - A) = w4 x (B - O4) and its derivative, solved for the
 * coupler's and the rocker's angular velocity and acceleration by Cramer's rule.
 *
 * Compiled by the benchmark itself (gcc -O2, a temporary folder) and called through ctypes.
 */
#include <math.h>

void fourbar(long n, const double *theta, const double *omega, const double *alpha,
             const double *p, double *out)
{
    /* p: O2x O2y O4x O4y r2 r3 r4 u w branch */
    const double ox = p[0], oy = p[1], qx = p[2], qy = p[3];
    const double r2 = p[4], r3 = p[5], r4 = p[6], u = p[7], w = p[8], side = p[9];
    const double diff = r3 * r3 - r4 * r4;
    for (long k = 0; k < n; ++k) {
        const double c = cos(theta[k]), s = sin(theta[k]);
        const double om = omega[k], al = alpha[k];
        /* crank tip A */
        const double ax = ox + r2 * c, ay = oy + r2 * s;
        const double vax = -om * r2 * s, vay = om * r2 * c;
        const double aax = -al * r2 * s - om * om * r2 * c, aay = al * r2 * c - om * om * r2 * s;
        /* B: circle (A, r3) and circle (O4, r4) */
        const double dx = qx - ax, dy = qy - ay;
        const double d2 = dx * dx + dy * dy, d = sqrt(d2);
        const double a = (diff + d2) / (2.0 * d);
        const double h = side * sqrt(r3 * r3 - a * a);
        const double bx = ax + (a * dx - h * dy) / d, by = ay + (a * dy + h * dx) / d;
        /* rates: w3 perp(e) - w4 perp(f) = -vA, e = B - A, f = B - O4 */
        const double ex = bx - ax, ey = by - ay, fx = bx - qx, fy = by - qy;
        const double det = ex * fy - ey * fx;
        /* x: -w3 ey + w4 fy = -vax,  y: w3 ex - w4 fx = -vay  (Cramer's rule) */
        const double idet = 1.0 / det;
        const double w3 = -(vax * fx + vay * fy) * idet;
        const double w4 = -(vax * ex + vay * ey) * idet;
        const double vbx = vax - w3 * ey, vby = vay + w3 * ex;
        /* a3 perp(e) - a4 perp(f) = -aA + w3^2 e - w4^2 f */
        const double rx = -aax + w3 * w3 * ex - w4 * w4 * fx;
        const double ry = -aay + w3 * w3 * ey - w4 * w4 * fy;
        const double a3 = (rx * fx + ry * fy) * idet;
        const double abx = aax - a3 * ey - w3 * w3 * ex, aby = aay + a3 * ex - w3 * w3 * ey;
        /* coupler point C */
        const double g = 1.0 / r3;
        const double tx = ex * g, ty = ey * g;
        const double cx_ = u * tx - w * ty, cy_ = u * ty + w * tx; /* C - A */
        const double vcx = vax - w3 * cy_, vcy = vay + w3 * cx_;
        const double acx = aax - a3 * cy_ - w3 * w3 * cx_, acy = aay + a3 * cx_ - w3 * w3 * cy_;
        double *o = out + 30 * k;
        /* O2, O4: standing still */
        o[0] = ox; o[1] = oy; o[2] = 0.0; o[3] = 0.0; o[4] = 0.0; o[5] = 0.0;
        o[6] = qx; o[7] = qy; o[8] = 0.0; o[9] = 0.0; o[10] = 0.0; o[11] = 0.0;
        o[12] = ax; o[13] = ay; o[14] = vax; o[15] = vay; o[16] = aax; o[17] = aay;
        o[18] = bx; o[19] = by; o[20] = vbx; o[21] = vby; o[22] = abx; o[23] = aby;
        o[24] = ax + cx_; o[25] = ay + cy_; o[26] = vcx; o[27] = vcy; o[28] = acx; o[29] = acy;
    }
}
