/* datafiles.c - the data files of a case checked while it is read (datafiles.h). */
#include "case/datafiles.h"

#include "plastic/hardening.h"

int mc_case_check_datafiles(const mc_scene *s, mc_error *err, const char **section,
                            const char **keyname)
{
    if (s->plasticity.enabled && s->plasticity.criterion == MC_CRITERION_VON_MISES &&
        s->plasticity.hardening == MC_HARDENING_TABLE) {
        static const double unit[] = {1.0, 1e6, 1e9}; /* table_unit: Pa, MPa, GPa */
        mc_hardening h;
        int rc = mc_hardening_table_read(s->plasticity.table, unit[s->plasticity.table_unit], &h,
                                         err);
        if (rc != MC_OK) {
            if (section)
                *section = "plasticity";
            if (keyname)
                *keyname = "table";
            if (err)
                mc_error_prefix(err, "[plasticity] table: ");
            return rc;
        }
        mc_hardening_free(&h);
    }
    return MC_OK;
}
