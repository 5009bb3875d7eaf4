/* summary_json.c - summary.json of the output contract (README.md, Outputs), built as a jansson document
 * from a scene and its results (see summary_json.h). Every allocation inside jansson is checked:
 * a failure gives MC_ERR_NOMEM, never a partial document.
 */
#include "pipeline/summary_json.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "kernels/kernel.h"

#define OUT_FORMAT_VERSION 1

typedef struct {
    int bad; /* an allocation inside jansson failed */
} jbuild;

/* Infinities (e.g. no pressure cap) and NaN become null: JSON has no such numbers. */
static json_t *jnum(double v) { return isfinite(v) ? json_real(v) : json_null(); }

static void jset(jbuild *b, json_t *obj, const char *key, json_t *v)
{
    if (!obj) {
        json_decref(v);
        b->bad = 1;
    } else if (json_object_set_new(obj, key, v) != 0) { /* steals v, also on failure */
        b->bad = 1;
    }
}

/* Attach a new child object; returns it (borrowed) or NULL when that failed. */
static json_t *jchild(jbuild *b, json_t *parent, const char *key, json_t *child)
{
    if (!child || !parent) {
        json_decref(child);
        b->bad = 1;
        return NULL;
    }
    if (json_object_set_new(parent, key, child) != 0) {
        b->bad = 1;
        return NULL;
    }
    return child;
}

/* Length of the valid UTF-8 sequence at s (RFC 3629: no overlongs, surrogates or > U+10FFFF),
 * 0 if invalid. */
static size_t utf8_seq(const unsigned char *s)
{
    unsigned char c = s[0];
    if (c < 0x80)
        return 1;
    size_t n;
    unsigned char lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF)
        n = 2;
    else if (c >= 0xE0 && c <= 0xEF) {
        n = 3;
        if (c == 0xE0)
            lo = 0xA0;
        if (c == 0xED)
            hi = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
        n = 4;
        if (c == 0xF0)
            lo = 0x90;
        if (c == 0xF4)
            hi = 0x8F;
    } else
        return 0;
    if (s[1] < lo || s[1] > hi)
        return 0;
    for (size_t k = 2; k < n; k++)
        if (s[k] < 0x80 || s[k] > 0xBF)
            return 0;
    return n;
}

/* A JSON string; bytes that are not UTF-8 (a Latin-1 file name) become '?' rather than failing. */
static json_t *jstr(const char *s)
{
    if (!s)
        return json_null();
    char buf[MC_PATH_MAX + 1];
    size_t k = 0;
    const unsigned char *u = (const unsigned char *)s;
    while (*u && k < MC_PATH_MAX) {
        size_t m = utf8_seq(u);
        if (m == 0 || k + m > MC_PATH_MAX) {
            buf[k++] = '?';
            u++;
            continue;
        }
        memcpy(buf + k, u, m);
        k += m;
        u += m;
    }
    buf[k] = '\0';
    return json_string(buf);
}

static json_t *jxyz(const double v[3])
{
    json_t *a = json_array();
    if (!a)
        return NULL;
    for (int k = 0; k < 3; k++)
        if (json_array_append_new(a, jnum(v[k])) != 0) {
            json_decref(a);
            return NULL;
        }
    return a;
}

static const char *shape_name(mc_shape s)
{
    switch (s) {
    case MC_SHAPE_FLAT: return "flat";
    case MC_SHAPE_SPHERE: return "sphere";
    case MC_SHAPE_CYLINDER: return "cylinder";
    case MC_SHAPE_ELLIPSOID: return "ellipsoid";
    }
    return "unknown";
}

/* ISO parameters, named as the standards write them, SI (m; Mr and Sdr in %), as o[name]. */
static void roughness_params(jbuild *b, json_t *o, const char *name, const mc_roughness_params *rp)
{
    mc_roughness_entry e[MC_ROUGHNESS_NENTRIES];
    int ne = mc_roughness_entries(rp, e);
    json_t *p = jchild(b, o, name, json_object());
    for (int k = 0; k < ne; k++)
        jset(b, p, e[k].name, jnum(e[k].value));
    jset(b, p, "cutoff_auto", json_boolean(rp->cutoff_auto));
    jset(b, p, "cutoff_clipped", json_boolean(rp->cutoff_clipped));
    jset(b, p, "evaluation_length", jnum(rp->evaluation_length));
    jset(b, p, "sampling_lengths", json_integer(rp->n_sampling));
    jset(b, p, "filtered", json_boolean(rp->filtered));
    if (rp->warning[0])
        jset(b, p, "warning", jstr(rp->warning));
}

static const char *rough_name(mc_roughness_type t)
{
    switch (t) {
    case MC_ROUGH_NONE: return "none";
    case MC_ROUGH_GAUSSIAN: return "gaussian";
    case MC_ROUGH_SELF_AFFINE: return "self_affine";
    case MC_ROUGH_FILE: return "file";
    }
    return "unknown";
}

static const char *load_name(mc_load_kind k)
{
    switch (k) {
    case MC_LOAD_FORCE: return "force";
    case MC_LOAD_FORCE_PER_LENGTH: return "force_per_length";
    case MC_LOAD_APPROACH: return "approach";
    case MC_LOAD_PRESSURE_FILE: return "pressure_file";
    }
    return "unknown";
}


/* JSON integers are signed 64-bit: a seed beyond INT64_MAX is written as a decimal string. */
static json_t *jseed(unsigned long long seed)
{
    if (seed <= (unsigned long long)INT64_MAX)
        return json_integer((json_int_t)seed);
    char t[32];
    snprintf(t, sizeof t, "%llu", seed);
    return json_string(t);
}

/* A roughness section's inputs: its type and that type's parameters; a file's name, the format
 * read and its missing and filled points. */
static void roughness_inputs(jbuild *b, json_t *o, const mc_roughness_spec *rs,
                             unsigned long long seed, const char *format, long missing,
                             long filled)
{
    const mc_roughness_type t = rs->type;
    jset(b, o, "type", jstr(rough_name(t)));
    if (t == MC_ROUGH_GAUSSIAN || t == MC_ROUGH_SELF_AFFINE) {
        jset(b, o, "seed", jseed(seed));
        jset(b, o, "rq", jnum(rs->rq));
    }
    if (t == MC_ROUGH_GAUSSIAN) {
        jset(b, o, "correlation_x", jnum(rs->correlation_x));
        jset(b, o, "correlation_y", jnum(rs->correlation_y));
    } else if (t == MC_ROUGH_SELF_AFFINE) {
        jset(b, o, "hurst", jnum(rs->hurst));
        jset(b, o, "rms_slope", jnum(rs->rms_slope));
        jset(b, o, "lambda_long", jnum(rs->lambda_long));
        jset(b, o, "lambda_short", jnum(rs->lambda_short));
    } else if (t == MC_ROUGH_FILE) {
        jset(b, o, "file", jstr(rs->file));
        jset(b, o, "format", jstr(format));
        jset(b, o, "missing_points", json_integer(missing));
        jset(b, o, "filled_points", json_integer(filled));
    }
}

/* roughness.body1 / body2 ([roughness2]): the body's section and inputs, its ISO parameters
 * before and after, and what of the plastic results is its own: whether it takes the residual
 * dent, and the file of its plastic strain (null where it stays elastic; with bodies = both
 * the one field of both bodies). */
static void body_roughness(jbuild *b, json_t *o, const mc_scene *s, const mc_results *r, int k)
{
    json_t *bo = jchild(b, o, k ? "body2" : "body1", json_object());
    const mc_roughness_spec *rs = k ? &s->roughness2 : &s->roughness;
    jset(b, bo, "section", jstr(k ? "roughness2" : "roughness"));
    roughness_inputs(b, bo, rs, rs->seed, r->body_file[k].format, r->body_file[k].missing,
                     r->body_file[k].filled);
    roughness_params(b, bo, "initial", &r->body_roughness_initial[k]);
    if (r->body_has_final)
        roughness_params(b, bo, "final", &r->body_roughness_final[k]);
    if (!r->plastic.enabled)
        return;
    const int dents = r->body_dents[k];
    jset(b, bo, "dents", json_boolean(dents));
    jset(b, bo, "residual_max", jnum(dents ? r->plastic.residual_max : 0.0));
    const int strain = dents && r->plastic_strain && s->plasticity.criterion ==
                                                         MC_CRITERION_VON_MISES;
    jset(b, bo, "plastic_strain", strain ? jstr("plastic_strain.npy") : json_null());
}

static void summary_inputs(jbuild *b, json_t *root, const mc_scene *s, const mc_results *r)
{
    const mc_grid *g = &r->grid;
    json_t *o = jchild(b, root, "mesh", json_object());
    jset(b, o, "nx", json_integer(g->nx));
    jset(b, o, "ny", json_integer(g->ny));
    jset(b, o, "dx", jnum(g->dx));
    jset(b, o, "dy", jnum(g->dy));
    jset(b, o, "periodic_x", json_boolean(g->periodic_x));
    jset(b, o, "periodic_y", json_boolean(g->periodic_y));

    o = jchild(b, root, "geometry", json_object());
    jset(b, o, "shape", jstr(shape_name(s->geometry.shape)));
    if (s->geometry.shape == MC_SHAPE_SPHERE || s->geometry.shape == MC_SHAPE_CYLINDER)
        jset(b, o, "radius", jnum(s->geometry.radius));
    if (s->geometry.shape == MC_SHAPE_ELLIPSOID) {
        jset(b, o, "radius_x", jnum(s->geometry.radius_x));
        jset(b, o, "radius_y", jnum(s->geometry.radius_y));
    }

    o = jchild(b, root, "materials", json_object());
    json_t *m = jchild(b, o, "body1", json_object());
    jset(b, m, "E", jnum(s->body1.E));
    jset(b, m, "nu", jnum(s->body1.nu));
    m = jchild(b, o, "body2", json_object());
    jset(b, m, "E", jnum(s->body2.E));
    jset(b, m, "nu", jnum(s->body2.nu));
    jset(b, m, "rigid", json_boolean(s->body2.rigid));
    jset(b, o, "estar", jnum(mc_combined_modulus(s->body1.E, s->body1.nu, s->body2.E,
                                                 s->body2.nu, s->body2.rigid)));

    o = jchild(b, root, "load", json_object());
    jset(b, o, "kind", jstr(load_name(s->load.kind)));
    if (s->load.kind == MC_LOAD_PRESSURE_FILE)
        jset(b, o, "pressure_file", jstr(s->load.pressure_file));
    else
        jset(b, o, "value", jnum(s->load.value));
    if (s->load.lubricant_pressure == MC_LUBRICANT_AUTO)
        jset(b, o, "lubricant_pressure", jstr("auto")); /* the value: lubrication.p_lub */
    else
        jset(b, o, "lubricant_pressure", jnum(s->load.lubricant_pressure));
    jset(b, o, "pressure_cap", jnum(s->load.pressure_cap));

    o = jchild(b, root, "roughness", json_object());
    roughness_inputs(b, o, &s->roughness, r->roughness_seed, r->surface_format,
                     r->surface_missing, r->surface_filled);
    if (r->has_roughness) /* the gap's (composite) roughness: with [roughness2] z1 + z2 */
        roughness_params(b, o, "initial", &r->roughness_initial);
    if (r->has_roughness_final) /* the final surface (elastic-plastic, running-in) */
        roughness_params(b, o, "final", &r->roughness_final);
    for (int k = 0; r->two_bodies && k < 2; k++) /* each body's surface (pipeline/bodies.h) */
        body_roughness(b, o, s, r, k);
}

/* The running-in (pipeline/runin.h): the forces and speeds, the hysteresis per force, and how
 * the steps went (rows: runin.csv). */
static void summary_runin(jbuild *b, json_t *root, const mc_scene *s, const mc_results *r)
{
    const mc_runin_summary *ri = &r->runin;
    json_t *o = jchild(b, root, "runin", json_object());
    json_t *forces = jchild(b, o, "forces", json_array());
    json_t *speeds = jchild(b, o, "speeds", json_array());
    json_t *rpm = jchild(b, o, "speeds_rpm", json_array());
    json_t *hyst = jchild(b, o, "hysteresis", json_array());
    int bad = !forces || !speeds || !rpm || !hyst;
    for (int k = 0; !bad && k < ri->nspeeds; k++)
        bad = json_array_append_new(speeds, jnum(s->runin.speeds[k])) != 0 ||
              json_array_append_new(rpm, jnum(s->runin.speeds[k] * 60.0 / (2.0 * M_PI))) != 0;
    for (int f = 0; !bad && f < ri->nforces; f++) {
        double F = s->runin.nforces > 0 ? s->runin.forces[f] : s->load.value;
        json_t *h = json_object();
        jset(b, h, "force", jnum(F));
        jset(b, h, "area", jnum(ri->hysteresis ? ri->hysteresis[f] : NAN));
        bad = json_array_append_new(forces, jnum(F)) != 0 ||
              !h || json_array_append_new(hyst, h) != 0;
    }
    if (bad)
        b->bad = 1;
    jset(b, o, "hysteresis_measure",
         jstr("integral of (mu_down - mu_up) over log10 of the speed (trapezoids over the "
              "speeds): mu times decades"));
    jset(b, o, "steps", json_integer(ri->nsteps));
    jset(b, o, "done", json_integer(ri->done));
    jset(b, o, "resumed_from", json_integer(ri->resumed_from));
    jset(b, o, "nominal_deflection", jstr(ri->deflection ? ri->deflection : ""));
    int converged = 1, plastic = 0, roots = 0, solves = 0;
    double worst = 0;
    for (int k = 0; k < ri->done; k++) {
        const mc_runin_row *w = &ri->rows[k];
        converged &= w->converged;
        plastic += w->plastic;
        roots += w->roots;
        solves += w->solves;
        worst = fmax(worst, w->root_error);
    }
    jset(b, o, "converged", json_boolean(converged));
    jset(b, o, "plastic_steps", json_integer(plastic));
    jset(b, o, "volume_roots", json_integer(roots));
    jset(b, o, "contact_solves", json_integer(solves));
    jset(b, o, "root_tolerance", jnum(s->lubrication.tolerance));
    jset(b, o, "root_error_max", jnum(worst));
    jset(b, o, "surface",
         jstr("surface_initial.npy, surface_final.npy: composite heights, m, positive towards "
              "the counter body; the fields (pressure.npy, ...) are those of the last step"));
}

/* How the stress stage computed (mc_stage_stress_layout): the depth rule and the windows, each with its
 * layers, its cells and their extent (cell edges, m), outside which the fields hold 0. */
static void stress_layout(jbuild *b, json_t *o, const mc_scene *s, const mc_results *r)
{
    const mc_stage_stress_layout *l = &r->stress_layout;
    const mc_grid *g = &r->grid;
    jset(b, o, "depth_rule", jstr(l->depth_auto ? "auto" : "given"));
    if (l->depth_auto) {
        jset(b, o, "patches", json_integer(l->patches));
        jset(b, o, "patch_radius", jnum(l->patch_radius));
    }
    jset(b, o, "loaded_cells", json_integer(l->loaded_cells));
    jset(b, o, "window", jstr(s->stress.window == MC_STRESS_WINDOW_FULL ? "full" : "auto"));
    jset(b, o, "windowed", json_boolean(l->windowed));
    json_t *arr = jchild(b, o, "windows", json_array());
    for (int k = 0; arr && k < l->nwindows; k++) {
        const mc_stage_stress_window *w = &l->window[k];
        json_t *e = json_object();
        const double x0 = mc_grid_x(g, w->i0) - 0.5 * g->dx, x1 = mc_grid_x(g, w->i1) + 0.5 * g->dx;
        const double y0 = mc_grid_y(g, w->j0) - 0.5 * g->dy, y1 = mc_grid_y(g, w->j1) + 0.5 * g->dy;
        json_t *v[5] = {json_pack("[ii]", w->k0, w->k1), json_pack("[ii]", w->i0, w->i1),
                        json_pack("[ii]", w->j0, w->j1), json_pack("[ff]", x0, x1),
                        json_pack("[ff]", y0, y1)};
        static const char *keys[5] = {"layers", "cells_x", "cells_y", "x", "y"};
        for (int q = 0; q < 5; q++)
            jset(b, e, keys[q], v[q]);
        jset(b, e, "method", jstr(w->sparse ? "direct" : "fft"));
        if (!e || json_array_append_new(arr, e) != 0)
            b->bad = 1;
    }
}

static void summary_results(jbuild *b, json_t *root, const mc_scene *s, const mc_results *r)
{
    const mc_contact_summary *cs = &r->contact;
    json_t *o = jchild(b, root, "contact", json_object());
    jset(b, o, "load", jnum(cs->load));
    jset(b, o, "solid_load", jnum(cs->solid_load));
    jset(b, o, "p_max", jnum(cs->p_max));
    jset(b, o, "area", jnum(cs->area));
    jset(b, o, "contact_ratio", jnum(cs->contact_ratio));
    jset(b, o, "approach", jnum(cs->approach));
    jset(b, o, "iterations", json_integer(cs->iterations));
    jset(b, o, "residual", jnum(cs->residual));
    /* a prescribed pressure was not solved for: no convergence is claimed either way */
    jset(b, o, "state",
         jstr(!cs->solved ? "prescribed" : cs->converged ? "converged" : "not_converged"));
    jset(b, o, "converged", cs->solved ? json_boolean(cs->converged) : json_null());
    jset(b, o, "solver", jstr(cs->solver));
    jset(b, o, "operator", jstr(mc_backend_name(cs->backend)));
    jset(b, o, "capped_cells", json_integer(cs->capped_cells));
    jset(b, o, "solved", json_boolean(cs->solved));
    if (cs->solved) {
        jset(b, o, "tolerance", jnum(s->solver.tolerance));
        jset(b, o, "max_iterations", json_integer(s->solver.max_iterations));
    }

    if (r->nlayers > 0) {
        const mc_stage_stress_summary *ss = &r->stress_summary;
        o = jchild(b, root, "stress", json_object());
        jset(b, o, "vm_max", jnum(ss->vm_max));
        jset(b, o, "vm_max_at", jxyz(ss->vm_max_at));
        jset(b, o, "hydro_at_vm_max", jnum(ss->hydro_at_vm_max));
        jset(b, o, "tresca_max", jnum(ss->tresca_max));
        jset(b, o, "tresca_max_at", jxyz(ss->tresca_max_at));
        jset(b, o, "layers", json_integer(r->nlayers));
        jset(b, o, "depth_min", jnum(ss->depth_min));
        jset(b, o, "depth_max", jnum(ss->depth_max));
        jset(b, o, "kernel", jstr(ss->kernel));
        jset(b, o, "friction", jnum(ss->friction));
        stress_layout(b, o, s, r);
    }

    if (r->plastic.enabled) {
        const mc_stage_plastic_summary *q = &r->plastic;
        o = jchild(b, root, "plastic", json_object());
        jset(b, o, "converged", json_boolean(q->converged));
        jset(b, o, "criterion", jstr(q->criterion));
        if (q->hardening[0])
            jset(b, o, "hardening", jstr(q->hardening));
        if (q->stress_points)
            jset(b, o, "stress_points", jstr(q->stress_points));
        if (q->kernel)
            jset(b, o, "kernel", jstr(q->kernel));
        if (q->iteration) { /* and how many increments the joint iteration left to the nested */
            int fallbacks = 0;
            for (int n = 0; q->steps && n < q->steps_done; n++)
                fallbacks += q->steps[n].joint_fallback;
            jset(b, o, "iteration", jstr(q->iteration));
            jset(b, o, "joint_fallbacks", json_integer(fallbacks));
        }
        jset(b, o, "yield_initial", jnum(q->yield_initial));
        jset(b, o, "vm_elastic_max", jnum(q->vm_elastic_max));
        jset(b, o, "elastic_shortcut", json_boolean(q->elastic_shortcut));
        jset(b, o, "load_steps", json_integer(q->load_steps));
        jset(b, o, "steps_done", json_integer(q->steps_done));
        jset(b, o, "outer_iterations", json_integer(q->outer_iterations));
        jset(b, o, "peq_max", jnum(q->peq_max));
        jset(b, o, "peq_max_at", jxyz(q->peq_max_at));
        jset(b, o, "plastic_volume", jnum(q->plastic_volume));
        jset(b, o, "residual_max", jnum(q->residual_max));
        jset(b, o, "depth", jnum(q->depth));
        jset(b, o, "depth_auto", json_boolean(q->depth_auto));
        jset(b, o, "dz", jnum(q->dz));
        jset(b, o, "nz", json_integer(q->nz));
        if (q->layering)
            jset(b, o, "layering", jstr(q->layering));
        if (q->group) { /* graded layers: each layer's centre depth and thickness */
            json_t *zc = jchild(b, o, "layer_depths", json_array());
            json_t *th = jchild(b, o, "layer_thickness", json_array());
            for (int k = 0, f = 0; zc && th && k < q->nz; f += q->group[k], k++) {
                json_array_append_new(zc, jnum((f + (q->group[k] - 1) / 2 + 0.5) * q->dz));
                json_array_append_new(th, jnum(q->group[k] * q->dz));
            }
        }
        json_t *w = jchild(b, o, "columns", json_object());
        jset(b, w, "i0", json_integer(q->i0));
        jset(b, w, "j0", json_integer(q->j0));
        jset(b, w, "nx", json_integer(q->wnx));
        jset(b, w, "ny", json_integer(q->wny));
        jset(b, o, "volume_cells", json_integer(q->volume_cells));
        if (q->stop_step > 0) { /* where and why it stopped (theory §9.5) */
            json_t *st = jchild(b, o, "stop", json_object());
            if (q->stop_runin_step > 0)
                jset(b, st, "runin_step", json_integer(q->stop_runin_step));
            jset(b, st, "load_step", json_integer(q->stop_step));
            jset(b, st, "load", jnum(q->stop_load));
            jset(b, st, "reason", jstr(q->stop_reason ? q->stop_reason : ""));
        } else
            jset(b, o, "stop", json_null());
    }

    if (r->lube.enabled) {
        const mc_stage_lube_summary *l = &r->lube;
        o = jchild(b, root, "lubrication", json_object());
        jset(b, o, "film", jstr(l->film));
        jset(b, o, "formula", l->formula[0] ? jstr(l->formula) : json_null());
        jset(b, o, "h_ehd", jnum(l->h_ehd));
        jset(b, o, "p_lub", jnum(l->p_lub));
        jset(b, o, "regime", jstr(l->regime ? l->regime : ""));
        jset(b, o, "psi_load", jnum(l->psi_load));
        jset(b, o, "psi_area", jnum(l->psi_area));
        jset(b, o, "pocket_height", jnum(l->pocket_height));
        jset(b, o, "mu", jnum(l->mu));
        jset(b, o, "psi", jstr(l->psi_kind));
        jset(b, o, "entrainment_speed", jnum(l->entrainment));
        jset(b, o, "slide_to_roll", jnum(l->srr));
        jset(b, o, "macro_load", jnum(l->macro_load));
        jset(b, o, "load_per_length", jnum(l->load_per_length));
        jset(b, o, "macro_radius", jnum(l->macro_radius));
        jset(b, o, "hertz_pressure", jnum(l->hertz_pressure));
        jset(b, o, "hertz_half_width", jnum(l->hertz_half_width));
        jset(b, o, "nominal_pressure", jnum(l->nominal_pressure));
        jset(b, o, "patch_load", jnum(l->patch_load));
        jset(b, o, "contact", jstr(l->whole ? "whole" : "patch"));
        jset(b, o, "nominal_area", jnum(l->nominal_area));
        if (l->whole)
            jset(b, o, "lubricant_profile", jstr(l->profile));
        if (l->crowned)
            jset(b, o, "hertz_half_length", jnum(l->hertz_half_length));
        jset(b, o, "volume", jnum(l->volume));
        jset(b, o, "volume_target", jnum(l->v_target));
        jset(b, o, "volume_rel_error", jnum(l->rel_error));
        jset(b, o, "contact_solves", json_integer(l->solves));
        jset(b, o, "converged", json_boolean(l->converged));
        jset(b, o, "note",
             jstr(l->crowned
                      ? "the whole crowned contact: the grid carries the macro ellipsoid and "
                        "F_N; the lubricant volume equilibrium is over the Hertz ellipse"
                  : l->whole
                      ? "the whole line contact: the strip carries the macro cylinder and w' "
                        "times its length; the lubricant volume equilibrium is over the Hertz "
                        "band |x| <= b"
                  : l->hertz_pressure > 0
                      ? "the patch stands for the centre of the macro line contact and carries "
                        "its Hertz pressure p_H as nominal pressure"
                      : "the scene's own load on the whole grid (no macro contact)"));
    }

    if (r->runin.enabled)
        summary_runin(b, root, s, r);

    o = jchild(b, root, "timing", json_object());
    jset(b, o, "total_s", jnum(r->timing.total_s));
    jset(b, o, "setup_s", jnum(r->timing.setup_s));
    jset(b, o, "contact_s", jnum(r->timing.contact_s));
    jset(b, o, "stress_s", jnum(r->timing.stress_s));
}
int mc_summary_json(const mc_scene *scene, const mc_results *res, const char *const *files,
                    int nfiles, const char *self, json_t **out, mc_error *err)
{
    jbuild b = {0};
    *out = NULL;
    json_t *root = json_object();
    if (!root)
        return mc_fail(err, MC_ERR_NOMEM, "summary.json: no memory to build the document");
    jset(&b, root, "format", json_string("microcontact-output"));
    jset(&b, root, "format_version", json_integer(OUT_FORMAT_VERSION));
    jset(&b, root, "case", jstr(scene->path));
    summary_inputs(&b, root, scene, res);
    summary_results(&b, root, scene, res);
    json_t *warn = jchild(&b, root, "warnings", json_array()); /* pipeline/warnings.h */
    for (int k = 0; warn && k < res->nwarnings; k++) {
        json_t *w = json_object();
        jset(&b, w, "code", jstr(res->warnings[k].code));
        jset(&b, w, "message", jstr(res->warnings[k].message));
        if (!w || json_array_append_new(warn, w) != 0) /* steals w, also on failure */
            b.bad = 1;
    }
    json_t *list = jchild(&b, root, "files", json_array());
    for (int k = 0; list && k < nfiles; k++)
        if (json_array_append_new(list, json_string(files[k])) != 0)
            b.bad = 1;
    if (list && self && json_array_append_new(list, json_string(self)) != 0)
        b.bad = 1;
    if (b.bad) {
        json_decref(root);
        return mc_fail(err, MC_ERR_NOMEM, "summary.json: no memory to build the document");
    }
    *out = root;
    return MC_OK;
}
