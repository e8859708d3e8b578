/*
 * The mappable-object table of a dictionary built at run time (co_od.h,
 * co_od_map_table): the generator writes the same table for its devices.
 */
#include "co_priv.h"

uint32_t co_od_map_table(const co_dev_t *dev, co_od_map_t *out, uint32_t cap)
{
    uint32_t n = 0U;

    for (uint32_t i = 0U; i < dev->od_count; i++) {
        const co_od_entry_t *e = &dev->od[i];
        const co_od_sub_t *r = co_od_rows(dev, e);
        for (uint32_t k = 0U; k < e->nsubs; k++) {
            for (uint32_t j = 0U; j < co_od_run_len(&r[k]); j++) {
                co_od_sub_t sd;
                const co_od_sub_t *s = co_od_row_sub(&r[k], j, &sd);
                uint32_t len = co_type_len(s->type);
                bool ram = (s->flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) == 0U;
                uint32_t off = ram ? co_od_off(e, s) : 0U;
                if (((s->flags & CO_SUB_MAP) == 0U) || (len == 0U)) {
                    continue;
                }
                if (n < cap) {
                    out[n].index = e->index;
                    out[n].sub = s->sub;
                    out[n].info = (uint8_t)((len - 1U) |
                                            (co_type_is_signed(s->type) ? CO_OD_MAP_SIGNED : 0U) |
                                            ((ram && ((off + 8U) > dev->ram_size))
                                                 ? CO_OD_MAP_AT_END : 0U));
                    out[n].off = (uint16_t)off;
                }
                n++;
            }
        }
    }
    return n;
}

