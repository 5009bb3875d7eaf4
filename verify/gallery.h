/* gallery.h - <reports>/index.md: one table of every suite (checks, failed, information rows,
 * regression gate, run time, link) and the paper-figure gallery in the paper's order.
 *
 * The gallery is driven by a manifest (gallery.c): one row per figure with the suite that draws
 * it, the PNG and CSV in <reports>/<suite>/, and a caption in three parts - what the paper
 * shows, what microcontact gets, where and why they differ. A figure from a suite written later
 * plugs in by adding a row; a figure whose suite is not in this build, has not been run into
 * <reports>, or did not draw the file, is listed as pending (not a failure).
 *
 * The index is built from what is on disk: each suite's <reports>/<suite>/result.json (written
 * by the harness) and its files. Captions may quote measured values, so that they stay true when
 * a number changes:
 *   {id}                 the measured value of check id of the row's suite (result.json),
 *   {suite:id}           the same from another suite,
 *   {csv:FILE:K=V,K2=V2:COL}  the column COL of the row of <reports>/<suite>/FILE whose columns
 *                        K, K2 read V, V2 (text comparison),
 * each optionally followed by |FMT (a printf conversion for one double, default %.4g) and/or
 * |pct (100 times the value, %.1f unless a FMT is given). A value that cannot be found prints
 * as "n/a". */
#ifndef MC_VERIFY_GALLERY_H
#define MC_VERIFY_GALLERY_H

#include <stddef.h>

typedef struct {
    const char *figure; /* the paper's figure, e.g. "Fig. 2-3"; rows of one figure are adjacent */
    const char *suite;  /* the suite that draws it */
    const char *png;    /* the figure, in <reports>/<suite>/ */
    const char *csv;    /* the data it is drawn from, beside it */
    const char *title;  /* one line */
    const char *paper;  /* what the paper shows */
    const char *ours;   /* what microcontact gets (placeholders allowed) */
    const char *differ; /* where and why they differ */
} vf_gallery_row;

/* The manifest, in the paper's order. */
const vf_gallery_row *vf_gallery_manifest(int *count);

/* Write <reports_dir>/index.md (through a temporary file). Returns 0, or -1 with a message. */
int vf_gallery_write(const char *reports_dir, char *msg, size_t msglen);

#endif
