/* gallery_manifest.c - the figures of reports/index.md, in the paper's order (gallery.h).
 *
 * One row per figure: the paper's figure, the suite and the files it writes, and the caption in
 * three parts. A suite written later plugs in by adding (or correcting) its row; until the suite
 * draws the file, the gallery lists the row as pending. Coordinates: the paper writes x for the
 * depth (our z) and sigma_x for our sigma_zz. */
#include "gallery.h"

static const vf_gallery_row manifest[] = {
    /* ---- Fig. 2-2: neighbouring asperities and the yield criterion ---- */
    {.figure = "Fig. 2-2 (a)",
     .suite = "neighbour_interaction",
     .png = "vm_vs_distance.png",
     .csv = "ratios.csv",
     .title = "maximum von Mises stress under an asperity against the distance of its "
              "neighbours, per pattern",
     .paper = "Hertzian asperities loaded side by side: the von Mises stress under the central "
              "asperity falls as the neighbours come closer, by up to about 16 %, because the "
              "neighbours' compressive fields add hydrostatic stress beneath it.",
     .ours = "Von Mises maximum under the central cell, normalised to the isolated cell, for a "
             "line of 3, a cross of 5 and 3x3, 5x5, 7x7 squares and the infinite square array, "
             "at centre distances d = 2a..8a (points: the stress operator; lines: exact "
             "Hamilton sums). At touching cells (d = 2a) the reduction is "
             "{csv:ratios.csv:pattern=line3,d_over_a=2.00:vm_ratio|pct} % of the isolated value "
             "left for the line, {csv:ratios.csv:pattern=square3x3,d_over_a=2.00:vm_ratio|pct} % "
             "for 3x3 and {csv:infinite.csv:d_over_a=2.00:vm_ratio|pct} % for the infinite "
             "array; the operator agrees with the exact sums to {infinite_array|%.1e} (worst "
             "absolute error of the ratio).",
     .differ = "The paper does not give its asperity radii and spacings (dossier "
               "plastic-lubrication 2.5), so its curve cannot be pinned to one pattern: its "
               "-16 % (red dotted line) is met by a 3x3 group at d ~ 2.1a or by larger fields "
               "at 2.3a-2.6a, never by a line or a cross of non-overlapping cells. The trend "
               "(closer and more neighbours, lower von Mises) is the same."},
    {.figure = "Fig. 2-2 (b)",
     .suite = "neighbour_interaction",
     .png = "hydro_vs_distance.png",
     .csv = "ratios.csv",
     .title = "hydrostatic stress at the von Mises maximum against the neighbour distance",
     .paper = "The hydrostatic (mean) stress for the same patterns and distances, beside the "
              "von Mises stress: the neighbours' compression adds to it, which is what lowers "
              "the von Mises stress.",
     .ours = "Hydrostatic stress at the von Mises maximum, normalised to the isolated cell: "
             "{csv:ratios.csv:pattern=square3x3,d_over_a=2.00:hydro_ratio|%.3f} times the "
             "isolated value for touching 3x3 cells, "
             "{csv:infinite.csv:d_over_a=2.00:hydro_ratio|%.3f} for the infinite array.",
     .differ = "As for (a): the same trend; the paper's geometry is unknown, so the magnitudes "
               "are not comparable one to one."},
    {.figure = "Fig. 2-2 (c)",
     .suite = "yield_criterion",
     .png = "centre_vs_neighbours.png",
     .csv = "centre_ratios.csv",
     .title = "permanent deformation of the centre asperity against its neighbours: "
              "stress-based yield against a pressure cap",
     .paper = "At p_H = 3139 MPa the neighbour patterns give different plastic deformation with "
              "the stress-based (von Mises) criterion, but the same with a limiting pressure: a "
              "pressure cap cannot see the neighbours' hydrostatic stress.",
     .ours = "The suite `yield_criterion` runs single, line, cross and 3x3 asperities (d = 2.5a) "
             "through the elastic-plastic stage with `criterion = von_mises` and `criterion = "
             "pressure_cap`, and plots the centre asperity's dent normalised to the single "
             "asperity.",
     .differ = "Matches the paper's statement: with von Mises the centre dent falls to 0.80 "
               "(line of 3), 0.62 (cross), 0.51 (3x3) and 0.42 (5x5) of the single asperity's, "
               "below even the elastic von Mises ratio (0.96 ... 0.87); with the cap it stays at "
               "1.000 ... 1.002. The paper's asperity geometry is unknown (dossier "
               "plastic-lubrication 2.5): the size of the effect is ours, not the paper's."},
    {.figure = "Fig. 2-2 (d)",
     .suite = "yield_criterion",
     .png = "profiles.png",
     .csv = "profiles.csv",
     .title = "residual surface displacement through the centre asperity, both criteria",
     .paper = "The plastic surface deformation of the neighbour patterns under the two yield "
              "criteria.",
     .ours = "Residual displacement (into the body) along the row through the centre asperity "
             "after unloading: von Mises criterion (solid) and pressure cap (dashed).",
     .differ = "The same contrast as (c): with the cap every asperity of a pattern gets the "
               "same dent (spread 7e-5 over a 3x3), with von Mises the corners, edges and "
               "centre differ by 42 %. Profiles, not the paper's geometry."},

    /* ---- Fig. 2-3: minimum evaluation depth of concentrated forces ---- */
    {.figure = "Fig. 2-3 (a)",
     .suite = "min_eval_depth",
     .png = "szz_vs_depth.png",
     .csv = "profile.csv",
     .title = "sigma_zz (paper: sigma_x) against depth z (paper: x) under a Hertz pressure, "
              "point forces and patch kernels",
     .paper = "sigma_x against the depth x for several meshes when every surface element is a "
              "concentrated force: near the surface the stress is wrong (it diverges under a "
              "force and vanishes between forces) down to a minimum evaluation depth that "
              "grows with the mesh size.",
     .ours = "In units of dx the curves of all meshes coincide (the elastic problem is "
             "scale-free), so one mesh (a/dx = 50) is drawn on three columns: under a force "
             "(node), at a cell corner and at an edge midpoint. The point kernel diverges at "
             "the node and vanishes at the corner near the surface, and is within 0.2 % of the "
             "closed form (Hamilton 1983) below {zmin_node_0.2pct|%.3f} dx; the patch kernel "
             "(microcontact's default) follows the closed form at every depth "
             "(largest error {patch_surface_corner|%.2f} (dx/a)^2 p0 at the surface, the "
             "pixelation of the sampled pressure).",
     .differ = "The paper plots in micrometres for each mesh; here the depth is in mesh units, "
               "where the meshes collapse onto one curve. With patch kernels there is no "
               "minimum evaluation depth at all: microcontact evaluates stresses at any depth."},
    {.figure = "Fig. 2-3 (b)",
     .suite = "min_eval_depth",
     .png = "zmin_vs_mesh.png",
     .csv = "zmin.csv",
     .title = "minimum evaluation depth against mesh size",
     .paper = "The minimum evaluation depth grows linearly with the mesh size: 1.3 um at the "
              "paper's 0.8 um mesh.",
     .ours = "z_min is proportional to dx for every tolerance: z_min = "
             "{fit_slope_1pct|%.3f} dx (1 %), {fit_slope_0.2pct|%.3f} dx (0.2 %), "
             "{fit_slope_0.1pct|%.3f} dx (0.1 %), intercepts below 1e-3 um. The paper's 1.3 um "
             "at 0.8 um is reproduced with a tolerance of {paper_eps|pct} % on sigma_zz "
             "(z_min(0.8 um) = {paper_zmin_0.8um|%.2f} um at 0.16 %).",
     .differ = "The paper does not state the accuracy behind its 1.3 um; the tolerance that "
               "reproduces it (about 0.17 %, the Poisson-summation estimate of elastic.md 3.6) "
               "is inferred, not quoted. The proportionality itself matches."},

    /* ---- Fig. 2-4: mesh convergence of the elastic-plastic result ---- */
    {.figure = "Fig. 2-4 (a)",
     .suite = "mesh_convergence",
     .png = "stress_depth.png",
     .csv = "stress_depth.csv",
     .title = "stress against depth at a contact point for meshes of 2.0 to 0.4 um",
     .paper = "The stress-depth curves at a contact point of a rough surface converge as the "
              "mesh is refined; from 0.8 um they are comparable, coarse meshes are too small.",
     .ours = "The suite `mesh_convergence` meshes one continuously defined rough surface at "
             "dx = 2.0, 1.6, 1.2, 0.8 and 0.4 um and plots the elastic von Mises stress against "
             "depth under one contact point.",
     .differ = "As the paper: the 0.8 um curve lies within 0.6 % (of the maximum) of the 0.4 um "
               "one, its maximum within 0.4 %; 2.0 and 1.6 um are 4 % and 10 % low and place "
               "the maximum 12 % and 9 % off in depth. The surface is ours (the paper's section "
               "is a measurement)."},
    {.figure = "Fig. 2-4 (b)",
     .suite = "mesh_convergence",
     .png = "plastic_vs_mesh.png",
     .csv = "measures.csv",
     .title = "plastic surface deformation against mesh size",
     .paper = "The plastic deformation of the surface against the mesh size: comparable from "
              "0.8 um, too small on a coarse mesh.",
     .ours = "Largest residual displacement, dent volume, integral of the plastic strain, "
             "largest plastic strain and plastic volume of the same surface after unloading, "
             "relative to the 0.4 um mesh.",
     .differ = "As the paper, the coarse meshes give too small a plastic deformation (largest "
               "dent {residual_max_rel_2.0|pct|%+.0f} %, {residual_max_rel_1.6|pct|%+.0f} %, "
               "{residual_max_rel_1.2|pct|%+.0f} % on 2.0, 1.6, 1.2 um); 0.8 um is within "
               "{residual_max_rel_0.8|pct|%+.1f} % in the largest dent, "
               "{dent_volume_rel_0.8|pct|%+.1f} % in dent volume, "
               "{peq_integral_rel_0.8|pct|%+.1f} % in integrated strain and "
               "{plastic_volume_rel_0.8|pct|%+.1f} % in plastic volume: comparable, not "
               "converged to the last per cent (the local maxima converge slowest)."},

    /* ---- benchmarks of the elastic-plastic method (no paper figure: its Section 2 cites
     * the validation of the method, dossier plastic-lubrication 2.5, 2.6) ---- */
    {.figure = "Benchmark: yield onset",
     .suite = "yield_onset",
     .png = "onset.png",
     .csv = "onset.csv",
     .title = "largest plastic strain just below and just above the Hertz yield onset",
     .paper = "The method yields on the von Mises stress of the volume, not on a limiting "
              "pressure: a Hertz contact must first yield below the surface at p0 = 1.613 Y "
              "(sphere, z = 0.481 a) and 1.794 Y (line, z = 0.704 b).",
     .ours = "Sphere and cylinder at 0.99 and 1.01 of the onset p0: nothing yields below, "
             "plastic strain appears above with its maximum at z/a = {point_above_depth|%.3f} "
             "(0.481) and z/b = {line_above_depth|%.3f} (0.704); the discrete elastic von Mises "
             "maxima are {point_vm_factor|%.4f} p0 (0.6200) and {line_vm_factor|%.4f} p0 "
             "(0.5575).",
     .differ = "Not a figure of the paper. The cylinder is a line contact: a grid periodic "
               "along y with one row, every volume cell a bar infinitely long along y (plane "
               "strain)."},
    {.figure = "Benchmark: Kogut-Etsion",
     .suite = "kogut_etsion",
     .png = "ke_interference.png",
     .csv = "ke.csv",
     .title = "interference of an elastic-perfectly plastic sphere on a rigid flat against load",
     .paper = "The Nelias group validated the semi-analytical method against the Kogut-Etsion "
              "(2002) FEM fits of a sphere on a rigid flat.",
     .ours = "w/w_c = {w_2|%.3f} at P/P_c = 2 (KE fit 1.593); the fast variant adds 6 P_c, "
             "the full one 4, 6, 10 and 14 P_c. Hertz (dashed) for contrast.",
     .differ = "The KE fits are remembered constants [S] (dossier 2.6)."},
    {.figure = "Benchmark: Kogut-Etsion",
     .suite = "kogut_etsion",
     .png = "ke_area.png",
     .csv = "ke.csv",
     .title = "contact area of the same sphere against load",
     .paper = "As above: the contact area against the KE fit.",
     .ours = "A/A_c = {A_2|%.3f} at P/P_c = 2 from the edge-extrapolated contact radius (KE fit "
             "1.578); the count of cells in contact (open points) overestimates it by about "
             "half a cell along the rim.",
     .differ = "As above."},
    {.figure = "Benchmark: Swift sphere",
     .suite = "swift_sphere",
     .png = "dent_convergence.png",
     .csv = "swift.csv",
     .title = "residual dent of the AISI 52100 Swift sphere against the mesh",
     .paper = "Residual dent of a rigid sphere (R = 15 mm, 2000 N) pressed into AISI 52100 "
              "(Swift law B = 1280 MPa, C = 4, n = 0.095) after unloading.",
     .ours = "Dent {dent_16|%.4f} um on 16^2 x 8 and {dent_32|%.4f} um on 32^2 x 12, the "
             "dossier's reference loop 0.2247 and 0.2418 um; the full variant adds 24^2 and "
             "48^2 and the observed order.",
     .differ = "The dossier's values come from a Python reference loop of the same method, not "
               "from a published FEM (Jacq 2002 was not retrievable): a regression, not "
               "converged physics."},

    /* ---- Fig. 3-1: the lubricant boundary condition ---- */
    {.figure = "Fig. 3-1 (a)",
     .suite = "lubricant_bc",
     .png = "pressure_profile.png",
     .csv = "profiles.csv",
     .title = "pressure profile with the lubricant floor p >= p_lub",
     .paper = "The boundary condition of the lubricated micro-contact: outside solid contact "
              "the surface carries the lubricant pressure p_lub, in solid contact the pressure "
              "exceeds it; the total load is shared between the solid contacts and the "
              "lubricant.",
     .ours = "A wavy surface (one period of a sinusoid, periodic, plane strain, "
             "{csv:summary.csv:case=lub:cells|%.0f} cells) under the same mean pressure without "
             "and with a lubricant pressure of {csv:summary.csv:case=lub:p_lub_over_pbar|pct} % "
             "of the mean pressure. The excess p - p_lub is Westergaard's solution for the "
             "remaining load (Johnson 1985 13.2). Measured: the pressure is exactly p_lub "
             "outside contact, within {csv:summary.csv:case=lub:profile_err_q0|%.1e} q0 of the "
             "closed form inside (|x| < 0.8a), the contact shrinks from "
             "{csv:summary.csv:case=dry:a_over_lambda|%.3f} to "
             "{csv:summary.csv:case=lub:a_over_lambda|%.3f} of the wavelength (closed form "
             "{csv:summary.csv:case=lub:a_ref_over_lambda|%.3f}), the solids carry "
             "{csv:summary.csv:case=lub:solid_load_fraction|pct} % of the load, and the split "
             "F_solid + p_lub A_free = F holds to {csv:summary.csv:case=lub:load_split|%.1g}. "
             "The paper's active-set solver gives the same pressure as cg to "
             "{active_vs_cg|%.0e} q0.",
     .differ = "The paper draws the condition schematically on a rough profile; here it is one "
               "sinusoid so that the closed form checks every cell. The floor, the shrinking "
               "contact and the load split are the same statement."},
    {.figure = "Fig. 3-1 (b)",
     .suite = "lubricant_bc",
     .png = "gap_displacement.png",
     .csv = "profiles.csv",
     .title = "surface displacement and gap with and without the lubricant pressure",
     .paper = "The displacement that the lubricant pressure causes: it acts on the surface "
              "outside the solid contacts too, so it deforms the surface and changes the "
              "lubricant pockets.",
     .ours = "Top: the loaded surface under the flat counter face (minus the gap), without "
             "and with the lubricant pressure; bottom: the elastic displacement u (into the "
             "body) relative to the crest. On a periodic patch a uniform pressure moves the "
             "surface rigidly (the same amount everywhere: checked to {rigid_shift|%.0e} of the "
             "displacement range), so what the lubricant changes is the solid load: the contact "
             "shrinks, the valleys spring back, and the mean gap (pocket volume per area) grows "
             "from {csv:summary.csv:case=dry:mean_gap_um|%.4f} um to "
             "{csv:summary.csv:case=lub:mean_gap_um|%.4f} um - the volume that the lubricant "
             "volume equilibrium balances against h_EHD.",
     .differ = "On a finite (non-periodic) patch the lubricant pressure would also bend the "
               "surface as a whole (a uniform strip load); the paper's patch stands for the "
               "centre of a macro contact, which the periodic patch models."},

    /* ---- Figs. 4-1 .. 4-3: running-in ---- */
    {.figure = "Fig. 4-1",
     .suite = "runin",
     .png = "runin_ra.png",
     .csv = "runin.csv",
     .title = "Ra against the mean lubrication pocket height, three normal forces",
     .paper = "During the speed run-down the surface runs in: Ra falls as the mean lubricant "
              "pocket height shrinks; on the run-up (elastic) Ra stays.",
     .ours = "The suite `runin` runs the twin-disc case of dossier plastic-lubrication 4.4 "
             "(cases/default.ini) at the paper's forces 1086, 2172, 3258 N on a 2 mm track, "
             "p_H = 1000, 1414, 1732 MPa (the track width is inferred from the paper's numbers, "
             "not stated by it), with a ground-like synthetic surface on a 51 um patch: run-down "
             "elastic-plastic, run-up elastic on the run-in surface.",
     .differ = "Same trends: Ra falls during every run-down (by 1.16 %, 0.74 %, 0.57 % at "
               "1086, 2172, 3258 N: the smoothing grows with the force, degressively; at the "
               "first force at every speed with solid contact, at the higher ones only from "
               "350 rpm on) and stays exactly on the run-up; the highest peak falls by 24 % (Sp). "
               "The paper's geometry, measured surfaces and friction constants are unknown "
               "(dossier 9), so the size of the change is ours: a synthetic patch smooths less "
               "than the paper's measured discs."},
    {.figure = "Fig. 4-2",
     .suite = "runin",
     .png = "runin_psi.png",
     .csv = "runin.csv",
     .title = "solid contact ratio psi against the mean pocket height",
     .paper = "The solid contact ratio psi (the share of the load the solids carry) against "
              "the mean lubricant pocket height, run-down and run-up.",
     .ours = "psi_load of every step of the suite `runin`, per force and phase.",
     .differ = "As for Fig. 4-1; as in the paper psi stays below 1 at 200 rpm for the higher "
               "forces (0.93 and 0.87; 1.00 at 1086 N): the lubricant volume keeps a share of "
               "the higher loads."},
    {.figure = "Fig. 4-3",
     .suite = "runin",
     .png = "runin_mu.png",
     .csv = "runin.csv",
     .title = "friction coefficient against speed: the running-in hysteresis for three forces",
     .paper = "The friction coefficient against speed differs between the run-down (with "
              "running-in) and the run-up on the smoothed surface: a hysteresis, largest at the "
              "lowest of the three normal forces.",
     .ours = "mu = psi mu_solid + (1 - psi) mu_fluid per step of the suite `runin`; an elastic "
             "material (dashed) gives no hysteresis.",
     .differ = "Same shape: the hysteresis H (area between the curves over log speed) is "
               "0.0024, 0.00099 and 0.00061 mu x decades at 1086, 2172, 3258 N, largest at the "
               "lowest force as in the paper; the curves of 1086 and 3258 N cross (mu rises "
               "with the force at 700 rpm, falls at 200 rpm), as the paper's change from rising "
               "to falling mu with force; the elastic material gives H = 0 exactly. "
               "mu_solid = 0.12 and mu_fluid = 0.03 are assumed: the level of mu is not the "
               "paper's."},
    /* ---- Figs. 4-1 .. 4-3 on the whole contact ---- */
    {.figure = "Fig. 4-1",
     .suite = "whole_contact",
     .png = "whole_ra.png",
     .csv = "runin.csv",
     .title = "the whole twin-disc contact: Ra against the mean pocket height",
     .paper = "As above: Ra falls during the run-down, stays on the run-up.",
     .ours = "The full variant of the suite `whole_contact` runs cases/twin_disc_whole.ini: the "
             "whole lubricated line contact of the 40 mm discs (R_x = 20 mm; the macro cylinder "
             "and the roughness across the Hertz band of the largest force plus 10 %, 1680 x "
             "128 cells of 0.8 um on a strip periodic along the face; the volume equilibrium "
             "over each force's band; docs/theory.md 11.4) at the paper's forces on a 2 mm "
             "track, p_H = 1000, 1414, 1732 MPa (an inference from its forces), 3000 to 100 "
             "rpm. The fast variant (make check) runs scaled 4 mm discs.",
     .differ = "Ra (of the heights on the widest band) falls over every run-down, by 0.68 %, "
               "1.07 % and 1.21 %, and stays on the run-up; the smoothing grows with force, "
               "degressively. At the first force it falls at every step whose solid share "
               "rises (checked; the 100 rpm step repeats the dry load of 200 rpm); at the "
               "higher forces the fast steps do not yield (shakedown: the first force's "
               "dry step already pressed the asperities harder), where the paper's curves fall "
               "throughout. The magnitudes depend on the synthetic surface (Sq 0.3 um) and are "
               "not the paper's measured discs."},
    {.figure = "Fig. 4-2",
     .suite = "whole_contact",
     .png = "whole_psi.png",
     .csv = "runin.csv",
     .title = "the whole twin-disc contact: solid contact ratio against the pocket height",
     .paper = "As above: psi below 100 % at 200 rpm for the higher forces.",
     .ours = "psi_load over the Hertz band, per step of the full-size case.",
     .differ = "psi at 200 rpm is 1.000, 0.912 and 0.848 at the three forces: below 1 for the "
               "higher forces, as in the paper (a checked trend); the film formula and the "
               "synthetic surface set the levels."},
    {.figure = "Fig. 4-3",
     .suite = "whole_contact",
     .png = "whole_mu.png",
     .csv = "runin.csv",
     .title = "the whole twin-disc contact: friction against speed, run-down and run-up",
     .paper = "As above: a hysteresis, largest at the lowest force; the curves of the forces "
              "cross.",
     .ours = "mu per step of the full-size case; H = the area between run-down and run-up over "
             "log10 speed.",
     .differ = "The hysteresis is 0.00268, 0.00217, 0.00170 mu x decades: largest at the first "
               "force, as in the paper (checked). The friction curves cross between 500 and 350 "
               "rpm (checked): mu rises with force at 3000 to 500 rpm and falls with force at "
               "350 rpm and below. mu_solid = 0.12 and mu_fluid = 0.03 are assumed: the level "
               "of mu is not the paper's. On the scaled discs of the fast variant the "
               "hysteresis is largest at the second force (the ring between the bands of "
               "fresh asperities outweighs the first force's share on so small a band)."},
};

const vf_gallery_row *vf_gallery_manifest(int *count)
{
    *count = (int)(sizeof manifest / sizeof manifest[0]);
    return manifest;
}
