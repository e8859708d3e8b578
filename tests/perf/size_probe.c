/*
 * Compiled by tools/bench-size, never linked: the sizes of the parts of a
 * size-dev node (size_dev.h), read back with nm, so that the node's RAM is
 * split into the core's structures and the dictionary's RAM image.
 */
#include <stddef.h>

#include "size_dev.h"

#define PROBE(name, size) char name[size]
/* (the PDO states, co_pdo_t, are the core's: at the end of the RAM image's
 * struct, co_dev_t.pdo_at) */
PROBE(probe_core, sizeof(co_node_t) + sizeof(((size_dev_ram_t *)0)->pdo));
/* the RAM image and the hook table (a node of a device without hooks has none) */
PROBE(probe_dict, sizeof(size_dev_node_t) - offsetof(size_dev_node_t, ram) -
                      sizeof(((size_dev_ram_t *)0)->pdo));
PROBE(probe_node, sizeof(size_dev_node_t));
