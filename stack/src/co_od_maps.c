/*
 * Walks of a whole dictionary (co_od_each_sub: the stored-layout signature
 * of co_store.c, and the mappable-object table of a dictionary built at run
 * time, co_od_map_table; the generator writes the same table for its
 * devices). Not in co_od.c: the per-frame lookup there keeps its helpers
 * inlined.
 */
#include "co_priv.h"

void co_od_each_sub(const co_dev_t *dev, co_od_visit_t visit, void *ctx)
{
    for (uint32_t i = 0U; i < dev->od_count; i++) {
        const co_od_entry_t *e = &dev->od[i];
        const co_od_sub_t *r = co_od_rows(dev, e);
        for (uint32_t k = 0U; k < e->nsubs; k++) {
            for (uint32_t j = 0U; j < co_od_run_len(&r[k]); j++) {
                co_od_sub_t sd;
                visit(ctx, e, co_od_row_sub(&r[k], j, &sd));
            }
        }
    }
}

typedef struct {
    const co_dev_t *dev;
    co_od_map_t *out;
    uint32_t cap;
    uint32_t n;
} map_walk_t;

/* (co_od_each_sub) a mappable sub-entry of fixed size: the next row */
static void add_row(void *ctx, const co_od_entry_t *e, const co_od_sub_t *s)
{
    map_walk_t *w = (map_walk_t *)ctx;
    uint32_t len = co_type_len(s->type);
    bool ram = (s->flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) == 0U;
    uint32_t off = ram ? co_od_off(e, s) : 0U;

    if (((s->flags & CO_SUB_MAP) == 0U) || (len == 0U)) {
        return;
    }
    if (w->n < w->cap) {
        co_od_map_t *m = &w->out[w->n];
        m->index = e->index;
        m->sub = s->sub;
        m->info = (uint8_t)((len - 1U) | (co_type_is_signed(s->type) ? CO_OD_MAP_SIGNED : 0U) |
                            ((ram && ((off + 8U) > w->dev->ram_size)) ? CO_OD_MAP_AT_END : 0U));
        m->off = (uint16_t)off;
    }
    w->n++;
}

uint32_t co_od_map_table(const co_dev_t *dev, co_od_map_t *out, uint32_t cap)
{
    map_walk_t w = {dev, out, cap, 0U};

    co_od_each_sub(dev, add_row, &w);
    return w.n;
}
