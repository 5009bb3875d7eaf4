/* whole_contact.c - suite `whole_contact`: the whole lubricated line contact (docs/theory.md
 * §11.4) against Hertz and McEwen, compared with the patch that stands for its centre, and its
 * running-in at the paper's pressures (Mevissen et al. 2025, Figs. 4-1 to 4-3).
 *
 * The discs are scaled down so that the whole Hertz width fits a small grid: R1 = R2 = 4 mm
 * (R_x = 2 mm) on a 2 mm track, forces 109, 218, 327 N give p_H = 1000, 1414, 1732 MPa (the
 * paper's pressures; the forces of its 40 mm discs scale with R_x). The film of such discs is that
 * of the 40 mm discs at about 28 times the speed (Pan-Hamrock: h ~ u^0.69 R_x^0.31 at equal p_H),
 * so the run-down of the fast variant starts at 60000 rpm. The full variant's running-in is the
 * full-size case cases/twin_disc_whole.ini itself (about 12 minutes on two cores). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "case/case.h"
#include "harness.h"
#include "runin_checks.h"
#include "kernels/invariants.h"
#include "pipeline/pipeline.h"
#include "pipeline/runin.h"
#include "reference/hertz.h"
#include "suites.h"
#include "vutil.h"

#define RPM (60.0 / (2.0 * M_PI)) /* rpm per rad/s */
#define FAST_SPEEDS "60000, 20000, 8000, 3000 rpm"

/* The lubricated discs, shared by every scene of the suite. */
#define DISCS DISCS_AT("60000")
#define DISCS_AT(rpm)                                                                              \
    "[lubrication]\nviscosity = 30 mPa*s\npressure_viscosity = 2e-8\nrpm = " rpm " rpm\n"       \
    "radius1 = 4 mm\nradius2 = 4 mm\nwidth = 2 mm\nmu_solid = 0.12\nmu_fluid = 0.03\n"
/* A vanishing given film: the equilibrium leaves the smooth contact's pressure in place. */
#define GIVEN "[lubrication]\nfilm = given\nfilm_thickness = 1e-6 nm\nwidth = 2 mm\n"
#define ROUGH                                                                                      \
    "[roughness]\ntype = gaussian\nrq = 0.3 um\ncorrelation_x = 4 um\ncorrelation_y = 24 um\n"     \
    "seed = 1\n"
#define SWIFT                                                                                      \
    "[plasticity]\nhardening = swift\nswift_B = 1280 MPa\nswift_C = 4\nswift_n = 0.095\n"          \
    "bodies = both\nload_steps = 1\ndz = 0.8 um\ndepth = %s\n"

static int parse(vf_ctx *ctx, const char *id, const char *text, mc_scene *sc)
{
    mc_error err = {0};
    int rc = mc_case_parse_text(text, "whole_contact_suite.ini", "", 0, NULL, sc, &err);
    if (rc != MC_OK)
        vf_fail(ctx, id, "%s", err.msg);
    return rc;
}

static int run_pipeline(vf_ctx *ctx, const char *id, const char *text, mc_results *r)
{
    mc_scene sc;
    memset(r, 0, sizeof *r);
    if (parse(ctx, id, text, &sc) != MC_OK)
        return 1;
    mc_error err = {0};
    int rc = mc_pipeline_run(&sc, r, &err);
    if (rc != MC_OK) {
        vf_fail(ctx, id, "%s", err.msg);
        return 1;
    }
    return 0;
}

/* The smooth whole contact, lubricated with a vanishing film (the equilibrium then leaves the
 * Hertz pressure in place), on a line grid (ny = 1: plane strain) with the stress at depth z:
 * against Hertz and McEwen. The patch at the same p_H: its centre under a uniform square. */
static void smooth(vf_ctx *ctx)
{
    char text[2048];
    snprintf(text, sizeof text,
             "[mesh]\nnx = %d\nny = 1\ndx = %s\nperiodic_y = yes\n"
             "[geometry]\nshape = cylinder\nradius = 2 mm\n"
             "[load]\nforce = 109 N\nlubricant_pressure = auto\n" GIVEN
             "[stress]\ndepths = 0.4 um, 17.3 um\n",
             128, "0.8 um");
    mc_results r;
    if (run_pipeline(ctx, "smooth_run", text, &r)) {
        mc_results_free(&r);
        return;
    }
    mc_hertz_line h;
    mc_error err = {0};
    const double nu = 0.3;
    /* two steel bodies (the defaults): E* = E / (2 (1 - nu^2)) */
    mc_hertz_line_from_load(r.lube.macro_radius, 0.5 * 210e9 / (1 - nu * nu),
                            r.lube.load_per_length, &h, &err);
    const mc_grid *g = &r.grid;
    double worst = 0, centre = 0;
    for (int i = 0; i < g->nx; i++) {
        const double x = mc_grid_x(g, i), e = fabs(r.pressure[i] - mc_hertz_line_pressure(&h, x));
        worst = vf_worst(worst, e / h.p0);
        if (fabs(x) < 0.5 * h.b)
            centre = vf_worst(centre, e / h.p0);
    }
    /* the pressure's square-root edge is resolved to a cell: the cell astride x = b carries an
     * error of order sqrt(dx/b) p0 of the profile's change across it (0.13 at dx = b/43); the
     * centre is exact to the contact tolerance and the Love kernel's quadrature */
    vf_check(ctx, "smooth_p_centre", "smooth whole contact: max |p - p_Hertz| / p_H, |x| < b/2",
             "Hertz line contact (Johnson 1985 §5.6)", 0, centre, 1e-3, VF_MAX);
    vf_check(ctx, "smooth_p_edge", "smooth whole contact: max |p - p_Hertz| / p_H, all cells",
             "Hertz; the edge cell's discretisation", 0, worst, 0.05, VF_MAX);
    vf_check(ctx, "smooth_p_h", "p_H of the scene's macro contact / Johnson's",
             "p_H = 2 w' / (pi b)", 1, r.lube.hertz_pressure / h.p0, 1e-12, VF_REL);
    double p0fit = 0;
    const double bfit = vu_fit_radius(&r, 1, h.b, 0.9, &p0fit);
    vf_check(ctx, "smooth_b", "half-width of the fitted pressure / Hertz b", "b^2 = 4 w' R / (pi E*)",
             1, bfit / h.b, 0.01, VF_REL);
    /* McEwen at the two depths, every cell (plane strain, nu = 0.3) */
    double sworst = 0, vm_whole = NAN;
    for (int k = 0; k < r.nlayers; k++)
        for (int i = 0; i < g->nx; i++) {
            double s[6], sim[6];
            const double x = mc_grid_x(g, i);
            mc_mcewen_normal(x / h.b, r.depths[k] / h.b, nu, s);
            for (int c = 0; c < 6; c++)
                sim[c] = r.stress[c][(size_t)k * g->nx + i] / h.p0;
            sworst = vf_worst(sworst, fabs(mc_von_mises(sim) - mc_von_mises(s)));
            if (k == 0 && i == g->nx / 2)
                vm_whole = mc_von_mises(sim);
        }
    /* the stress inherits the pressure's edge-cell error, decayed with depth (Flamant ~ 1/r) */
    vf_check(ctx, "smooth_vm", "smooth whole contact: max |sigma_vM - McEwen| / p_H, z = 0.4 and 17.3 um",
             "McEwen (1949), plane strain", 0, sworst, 0.02, VF_MAX);
    mc_results_free(&r);

    /* the patch at the same p_H: a uniform square of p_H, free edges (its centre) */
    snprintf(text, sizeof text,
             "[mesh]\nnx = 48\nny = 48\ndx = 0.8 um\n"
             "[load]\nforce = 109 N\nlubricant_pressure = auto\n" GIVEN
             "macro_radius = 2 mm\n[stress]\ndepths = 0.4 um\n");
    if (run_pipeline(ctx, "patch_run", text, &r) == 0) {
        const mc_grid *pg = &r.grid;
        double sim[6];
        const size_t c0 = (size_t)(pg->ny / 2) * pg->nx + pg->nx / 2;
        for (int c = 0; c < 6; c++)
            sim[c] = r.stress[c][c0] / r.lube.hertz_pressure;
        vf_info(ctx, "patch_vm_centre", "patch: sigma_vM / p_H at its centre, z = 0.4 um",
                "a uniform square of p_H: no macro field", NAN,
                mc_von_mises(sim));
        vf_info(ctx, "whole_vm_centre", "whole contact: sigma_vM / p_H at the centre, z = 0.4 um",
                "McEwen: (1 - 2 nu) = 0.4 at the surface", NAN, vm_whole);
    }
    mc_results_free(&r);
}

/* The whole crowned contact (shape = ellipsoid on a free grid), smooth, with a film of 0.1 nm (the
 * fluid then takes a few MPa in the ellipse's last cells and leaves the Hertz pressure): the elliptical Hertz contact (Johnson 1985 §4.2; reference/hertz.h, itself checked
 * against the contact solver in tests/test_hertz.c): p_max, the nominal area pi a b. */
static void crowned(vf_ctx *ctx)
{
    mc_results r;
    const char *text = "[mesh]\nnx = 64\nny = 288\ndx = 0.8 um\n"
                       "[geometry]\nshape = ellipsoid\nradius_x = 2 mm\nradius_y = 20 mm\n"
                       "[load]\nforce = 3 N\nlubricant_pressure = auto\n"
                       "[lubrication]\nfilm = given\nfilm_thickness = 0.1 nm\ntolerance = 1e-3\n";
    if (run_pipeline(ctx, "crowned_run", text, &r) == 0) {
        const mc_stage_lube_summary *l = &r.lube;
        double pmax = 0;
        for (size_t i = 0; i < mc_grid_cells(&r.grid); i++)
            pmax = vf_worst(pmax, r.pressure[i]);
        /* 27 cells across the short semi-axis: the peak is the centre's, within 0.5 % */
        vf_check(ctx, "crowned_p0", "crowned whole contact: p_max / elliptical Hertz p0",
                 "Johnson (1985) §4.2", 1, pmax / l->hertz_pressure, 5e-3, VF_REL);
        /* the ellipse's cells against its area: the boundary cells, ~ perimeter dx / area */
        vf_check(ctx, "crowned_area", "crowned: nominal area (cells in the ellipse) / pi a b",
                 "the Hertz ellipse", 1, l->nominal_area / (M_PI * l->hertz_half_width *
                                                            l->hertz_half_length),
                 0.02, VF_REL);
        vf_info(ctx, "crowned_axes", "crowned: a / b of the Hertz ellipse (R_y / R_x = 10)",
                "Hamrock & Brewe: 1.0339 (R_y/R_x)^0.636 = 4.47", NAN,
                l->hertz_half_length / l->hertz_half_width);
    }
    mc_results_free(&r);
}

/* The peak plastic strain in the outer ring of cells (within `ring` cells of a free edge of the
 * plastic window) over the peak inside it: the patch's edge artefact. */
static double ring_ratio(const mc_results *r, int ring, int free_y)
{
    const mc_stage_plastic_summary *ps = &r->plastic;
    double outer = 0, inner = 0;
    for (int k = 0; k < ps->nz; k++)
        for (int j = 0; j < ps->wny; j++)
            for (int i = 0; i < ps->wnx; i++) {
                const double v = r->plastic_strain[((size_t)k * ps->wny + j) * ps->wnx + i];
                const int edge = i < ring || i >= ps->wnx - ring ||
                                 (free_y && (j < ring || j >= ps->wny - ring));
                if (edge)
                    outer = vf_worst(outer, v);
                else
                    inner = vf_worst(inner, v);
            }
    return inner > 0 ? outer / inner : NAN;
}

/* The rough patch and the rough whole contact at the same p_H, elastic-plastic, lubricated, at
 * the slowest speed (where the solids carry the most). */
static void rough_compare(vf_ctx *ctx)
{
    char text[2048];
    mc_results rp, rw;
    snprintf(text, sizeof text,
             "[mesh]\nnx = 48\nny = 48\ndx = 0.8 um\n" ROUGH
             "[load]\nforce = 109 N\nlubricant_pressure = auto\n" DISCS_AT("3000") SWIFT,
             "2.4 um");
    int okp = run_pipeline(ctx, "patch_plastic", text, &rp) == 0;
    snprintf(text, sizeof text,
             "[mesh]\nnx = 96\nny = 48\ndx = 0.8 um\nperiodic_y = yes\n"
             "[geometry]\nshape = cylinder\nradius = 2 mm\n" ROUGH
             "[load]\nforce = 109 N\nlubricant_pressure = auto\n" DISCS_AT("3000") SWIFT,
             "2.4 um");
    int okw = run_pipeline(ctx, "whole_plastic", text, &rw) == 0;
    if (okp && okw) {
        vf_text(ctx, "Patch against whole contact at p_H = %.0f MPa (rough, elastic-plastic, "
                     "3000 rpm): psi_load %.4f against %.4f, p_lub %.1f against %.1f MPa (the "
                     "band's mean), peak plastic strain %.4g against %.4g.\n\n",
                rp.lube.hertz_pressure * 1e-6, rp.lube.psi_load, rw.lube.psi_load,
                rp.lube.p_lub * 1e-6, rw.lube.p_lub * 1e-6, rp.plastic.peq_max,
                rw.plastic.peq_max);
        vf_info(ctx, "patch_ring_ratio",
                "patch: peak plastic strain within 2 cells of its free edge / inside", 
                "the pressure steps from p_H to 0 at the edge", NAN, ring_ratio(&rp, 2, 1));
        vf_info(ctx, "whole_ring_ratio",
                "whole contact: peak plastic strain within 2 cells of the grid's x edges / inside",
                "Hertz pressure falls to 0 at |x| = b inside the grid", NAN,
                ring_ratio(&rw, 2, 0));
        vf_info(ctx, "patch_psi", "patch: psi_load", "", NAN, rp.lube.psi_load);
        vf_info(ctx, "whole_psi", "whole contact: psi_load", "", NAN, rw.lube.psi_load);
    }
    mc_results_free(&rp);
    mc_results_free(&rw);
}

/* The running-in: the fast variant (and the elastic twin of either) on the scaled discs of the
 * header; the full variant is the full-size case itself, cases/twin_disc_whole.ini (R_x = 20 mm,
 * 1680 x 128 cells of 0.8 um, three forces, six speeds), read from the repository's cases/ as
 * `make verify` and `make bless` run it (from the repository root). */
#define FULL_CASE "cases/twin_disc_whole.ini"
static int run_runin(vf_ctx *ctx, int fast, int plastic, mc_results *r)
{
    const char *id = plastic ? "runin" : "runin_elastic";
    mc_scene sc;
    memset(r, 0, sizeof *r);
    mc_error err = {0};
    if (!fast && plastic) {
        if (mc_case_load(FULL_CASE, 0, NULL, &sc, &err) != MC_OK) {
            vf_fail(ctx, id, "%s (the full variant runs " FULL_CASE " from the repository root)",
                    err.msg);
            return 1;
        }
    } else {
        char plas[512] = "", text[4096];
        if (plastic)
            snprintf(plas, sizeof plas, SWIFT, "3.2 um");
        snprintf(text, sizeof text,
                 "[mesh]\nnx = 176\nny = 16\ndx = 0.8 um\nperiodic_y = yes\n"
                 "[geometry]\nshape = cylinder\nradius = 2 mm\n" ROUGH
                 "[load]\nforce = 109 N\nlubricant_pressure = auto\n" DISCS
                 "[runin]\nforces = 109 N, 218 N\nspeeds = " FAST_SPEEDS "\n%s",
                 plas);
        if (parse(ctx, id, text, &sc) != MC_OK)
            return 1;
    }
    int rc = mc_runin_run(&sc, NULL, r, &err);
    if (rc != MC_OK)
        vf_fail(ctx, id, "%s", err.msg);
    return rc != MC_OK;
}

static void runin_figures(vf_ctx *ctx, const mc_runin_summary *ri)
{
    FILE *f = vf_open(ctx, "runin.csv");
    if (!f)
        return;
    fprintf(f, "force,phase,rpm,h_ehd_um,p_lub_MPa,psi_load,psi_area,pocket_um,mu,Ra_um,Sa_um,plastic\n");
    for (int k = 0; k < ri->done; k++) {
        const mc_runin_row *w = &ri->rows[k];
        fprintf(f, "%.0f,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.8g,%.8g,%.8g,%d\n", w->force,
                w->up ? "up" : "down", w->speed * RPM, w->h_ehd * 1e6, w->p_lub * 1e-6,
                w->psi_load, w->psi_area, w->pocket_height * 1e6, w->mu, w->ra * 1e6, w->sa * 1e6,
                w->plastic);
    }
    vf_close(ctx, f);
    const int m = ri->nspeeds, nf = ri->nforces;
    const char *figs[3][4] = {
        {"whole_ra.png", "Whole contact: Ra against the mean pocket height (paper Fig. 4-1)",
         "h_{pocket} [um]", "Ra [um]"},
        {"whole_psi.png", "Whole contact: solid contact ratio against the pocket height (paper Fig. 4-2)",
         "h_{pocket} [um]", "psi_{load}"},
        {"whole_mu.png", "Whole contact: friction against disc speed, run-down and run-up (paper "
         "Fig. 4-3)", "disc speed [rpm]", "mu"}};
    const char *cols[3] = {"8:10", "8:6", "3:9"};
    char plot[4096];
    for (int g = 0; g < 3; g++) {
        size_t o = (size_t)snprintf(plot, sizeof plot,
                                    "set datafile separator ','\nset grid\nset key outside right\n"
                                    "set xlabel '%s'\nset ylabel '%s'\n%splot",
                                    figs[g][2], figs[g][3], g == 2 ? "set logscale x\n" : "");
        for (int ff = 0; ff < nf && o < sizeof plot; ff++) {
            const double F = ri->rows[2 * m * ff].force;
            for (int ph = 0; ph < 2 && o < sizeof plot; ph++)
                o += (size_t)snprintf(
                    plot + o, sizeof plot - o,
                    "%s'runin.csv' every ::1 using ($1 == %.0f && strcol(2) eq '%s' ? $%.*s : "
                    "1/0):%s with linespoints pt %d lc %d title '%.0f N %s'",
                    ff || ph ? ", " : " ", F, ph ? "up" : "down",
                    (int)(strchr(cols[g], ':') - cols[g]), cols[g], strchr(cols[g], ':') + 1,
                    ph ? 6 : 7, ff + 1, F, ph ? "run-up" : "run-down");
        }
        vf_plot(ctx, figs[g][0], figs[g][1], plot);
    }
}

static void runin(vf_ctx *ctx, int fast)
{
    mc_results r, e;
    if (run_runin(ctx, fast, 1, &r)) {
        mc_results_free(&r);
        return;
    }
    const mc_runin_summary *ri = &r.runin;
    const int m = ri->nspeeds, nf = ri->nforces;
    char id[64], q[200];
    double hmax_other = -INFINITY;
    vf_text(ctx, "| step | F_N [N] | phase | speed [rpm] | h_EHD [um] | p_lub [MPa] | psi_load | "
                 "h_pocket [um] | mu | Ra [um] | plastic |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < ri->done; k++) {
        const mc_runin_row *w = &ri->rows[k];
        vf_text(ctx, "| %d | %.0f | %s | %.0f | %.3f | %.1f | %.4f | %.3f | %.5f | %.5f | %s |\n",
                k + 1, w->force, w->up ? "up" : "down", w->speed * RPM, w->h_ehd * 1e6,
                w->p_lub * 1e-6, w->psi_load, w->pocket_height * 1e6, w->mu, w->ra * 1e6,
                w->plastic ? "yes" : "");
    }
    vf_text(ctx, "\n");
    for (int f = 0; f < nf; f++) {
        const mc_runin_row *first = &ri->rows[2 * m * f], *last = &ri->rows[2 * m * f + m - 1];
        const double ra_before = f == 0 ? r.roughness_initial.Ra : ri->rows[2 * m * f - 1].ra;
        vf_runin_ra_checks(ctx, ri, f, ra_before);
        /* Ra at every run-down step that loads the asperities harder than the step before (its
         * solid share psi_load rose; a dry step after a dry step repeats the same load): it
         * must fall at the first force; at the higher forces the fast steps carry less solid
         * load than the first force's dry steps already did (shakedown: information) */
        int quiet = 0;
        double prev = ra_before, psi_prev = 0;
        for (int k = 0; k < m; k++) {
            quiet += first[k].psi_load > psi_prev + 1e-9 && !(first[k].ra < prev * (1 - 1e-6));
            prev = first[k].ra;
            psi_prev = first[k].psi_load;
        }
        snprintf(id, sizeof id, "quiet_mixed_steps_F%d", f + 1);
        snprintf(q, sizeof q, "F_N = %.0f N: run-down steps with a rising solid share where Ra "
                 "did not fall", first->force);
        if (f == 0 && !fast)
            vf_check(ctx, id, q, "paper Fig. 4-1: Ra falls continuously on the run-down", 0,
                     quiet, 0, VF_MAX);
        else
            vf_info(ctx, id, q, f ? "shakedown: see the text" : "full variant: a check", NAN,
                    quiet);
        const mc_runin_row *before = f == 0 ? NULL : &ri->rows[2 * m * f - 1];
        const struct {
            const char *id, *what;
            double from, to;
        } peaks[] = {{"ra_change", "Ra", ra_before, last->ra},
                     {"rpk_change", "Rpk (ISO 13565-2)",
                      before ? before->rpk : r.roughness_initial.Rpk, last->rpk},
                     {"sp_change", "Sp (highest peak, ISO 25178-2)",
                      before ? before->sp : r.roughness_initial.Sp, last->sp}};
        for (size_t q2 = 0; q2 < sizeof peaks / sizeof peaks[0]; q2++) {
            snprintf(id, sizeof id, "%s_F%d", peaks[q2].id, f + 1);
            snprintf(q, sizeof q, "F_N = %.0f N: change of %s over the run-down, %%", first->force,
                     peaks[q2].what);
            vf_info(ctx, id, q, "running-in lowers the peaks", NAN,
                    100.0 * (peaks[q2].to / peaks[q2].from - 1.0));
        }
        snprintf(id, sizeof id, "hysteresis_F%d", f + 1);
        snprintf(q, sizeof q, "F_N = %.0f N: hysteresis H (mu x decades of speed)", first->force);
        vf_info(ctx, id, q, "paper Fig. 4-3 (shape only)", NAN, ri->hysteresis[f]);
        snprintf(id, sizeof id, "psi_slowest_F%d", f + 1);
        snprintf(q, sizeof q, "F_N = %.0f N: psi_load at the slowest speed", first->force);
        vf_info(ctx, id, q, "", NAN, last->psi_load);
        /* psi at 200 rpm of the 40 mm discs (the full variant's speeds include it) */
        for (int k = 0; !fast && f > 0 && k < m; k++)
            if (fabs(first[k].speed * RPM - 200.0) < 0.5) {
                snprintf(id, sizeof id, "psi_200rpm_F%d", f + 1);
                snprintf(q, sizeof q, "F_N = %.0f N: psi_load at 200 rpm", first->force);
                vf_check(ctx, id, q, "paper Fig. 4-2: psi < 100 % at 200 rpm for the higher "
                         "forces", 1, first[k].psi_load, 1 - 1e-6, VF_MAX);
            }
        if (f > 0)
            hmax_other = vf_worst(hmax_other, ri->hysteresis[f]);
    }
    vf_check(ctx, "hysteresis_positive", "-H at the first force (passes when H > 1e-6)",
             "paper: mu_up below mu_down", 0, -ri->hysteresis[0], -1e-6, VF_MAX);
    /* largest at the first force: a check on the full-size contact; information on the scaled
     * discs of the fast variant, where a higher force widens the band (b ~ sqrt F) over a ring of
     * fresh asperities that run in only at the higher force and outweigh the first force's
     * share on so small a band (theory §11.4) */
    if (fast)
        vf_info(ctx, "hysteresis_ratio", "max H at the higher forces / H at the first",
                "paper: largest at the lowest force (full variant: a check)", NAN,
                hmax_other / ri->hysteresis[0]);
    else
        vf_check(ctx, "hysteresis_ratio", "max H at the higher forces / H at the first",
                 "paper Fig. 4-3: the hysteresis is largest at the lowest force", 0,
                 hmax_other / ri->hysteresis[0], 1, VF_MAX);
    /* the paper's change from mu rising with force (thin asperity share at high speed) to mu
     * falling with force: mu(last force) - mu(first force) changes sign over the run-down speeds
     * (by more than 1e-4 either way: beyond the root tolerance's effect on mu) */
    double dmax = -INFINITY, dmin = INFINITY;
    for (int k = 0; k < m; k++) {
        const double d = ri->rows[2 * m * (nf - 1) + k].mu - ri->rows[k].mu;
        dmax = vf_worst(dmax, d);
        dmin = vf_least(dmin, d);
    }
    const double cross = fmin(dmax, -dmin); /* > 0 when both signs occur */
    if (fast)
        vf_info(ctx, "mu_curves_cross", "min(max d, -min d), d = mu(last force) - mu(first) over "
                "the run-down", "paper Fig. 4-3: the curves of the forces cross (full variant)",
                NAN, cross);
    else
        vf_check(ctx, "mu_curves_cross", "min(max d, -min d), d = mu(last force) - mu(first) "
                 "over the run-down (> 1e-4: the curves cross)",
                 "paper Fig. 4-3: mu rises with force at high speed, falls at low speed", 0,
                 -cross, -1e-4, VF_MAX);
    vf_info(ctx, "ra_initial", "Ra of the initial heights on the widest Hertz band, um", "", NAN,
            r.roughness_initial.Ra * 1e6);
    vf_info(ctx, "ra_final", "Ra of the run-in heights, um", "", NAN, r.roughness_final.Ra * 1e6);
    runin_figures(ctx, ri);
    /* the elastic material: no hysteresis at all (down and up are the same solves) */
    if (run_runin(ctx, 1, 0, &e) == 0) {
        const mc_runin_summary *ei = &e.runin;
        const int me = ei->nspeeds;
        double dev = 0;
        for (int ff = 0; ff < ei->nforces; ff++)
            for (int k = 0; k < me; k++)
                dev = vf_worst(dev, fabs(ei->rows[2 * me * ff + k].mu -
                                         ei->rows[2 * me * ff + 2 * me - 1 - k].mu));
        vf_check(ctx, "elastic_identity", "elastic material: max |mu_down - mu_up| at equal speed",
                 "nothing runs in: identical solves", 0, dev, 0, VF_MAX);
    }
    mc_results_free(&r);
    mc_results_free(&e);
}

int vf_suite_whole_contact(vf_ctx *ctx, int fast)
{
    vf_text(ctx,
            "The whole lubricated line contact (docs/theory.md §11.4): the grid carries the "
            "macro cylinder R_x and the roughness across the whole Hertz band of the largest "
            "force plus 10 %%, on a strip periodic along the face; the strip carries w' times "
            "its length and the lubricant volume equilibrium holds over the band |x| <= b with "
            "one lubricant pressure in the valleys. The smooth, crowned and patch comparisons "
            "use scaled-down discs: R1 = R2 = 4 mm (R_x = 2 mm) on a 2 mm track; 109, 218, 327 "
            "N give the paper's 1000, 1414, 1732 MPa (an inference from the paper's forces, not "
            "its statement). The running-in: the full variant runs the full-size case "
            "cases/twin_disc_whole.ini (40 mm discs, R_x = 20 mm, 1680 x 128 cells of 0.8 um, "
            "the paper's three forces, 3000 to 100 rpm; about 12 minutes on two cores); the "
            "fast variant (make check) the scaled discs at two forces, speeds from 60000 rpm "
            "giving the 40 mm discs' films of 3000 rpm and below.\n\n"
            "Checks: the smooth whole contact is Hertz's (pressure, half-width) and McEwen's "
            "(the subsurface field); the running-in's trends: Ra never rises during a run-down "
            "and ends lower, stays during the run-up, the hysteresis is positive, and an "
            "elastic material has none; in the full variant also the paper's Figs. 4-1 to 4-3: "
            "Ra falls at every step whose solid share rises at the first force, psi < 1 at 200 rpm "
            "for the higher forces, the hysteresis is largest at the first force, the friction "
            "curves of the forces cross. At the higher forces the fast steps do not yield "
            "(shakedown: the first force's dry 100 rpm step pressed the asperities harder than "
            "their mixed steps do): information. On the scaled discs of the fast variant the "
            "hysteresis is largest at the second force: a higher force widens the Hertz band "
            "(b ~ sqrt F_N), and the ring between the bands carries fresh asperities that run "
            "in only at the higher force: information there. Information: the patch that "
            "stands for the centre against the whole contact at the same p_H (its missing macro "
            "field near the surface, its edge ring, psi).\n\n");
    smooth(ctx); /* the same in both variants: at dx = 0.4 um the vanishing film's root is
                  * below the contact tolerance's resolution (the equilibrium stops) */
    crowned(ctx);
    rough_compare(ctx);
    runin(ctx, fast);
    return 0;
}
