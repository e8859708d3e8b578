#include "co_crc16.h"

uint16_t co_crc16(uint16_t crc, const uint8_t *data, uint32_t len)
{
    /* Nibble table: 32 bytes of flash instead of 512. */
    static const uint16_t tab[16] = {
        0x0000U, 0x1021U, 0x2042U, 0x3063U, 0x4084U, 0x50A5U, 0x60C6U, 0x70E7U,
        0x8108U, 0x9129U, 0xA14AU, 0xB16BU, 0xC18CU, 0xD1ADU, 0xE1CEU, 0xF1EFU
    };

    for (uint32_t i = 0U; i < len; i++) {
        crc = (uint16_t)((uint16_t)(crc << 4U) ^ tab[((crc >> 12U) ^ (data[i] >> 4U)) & 0x0FU]);
        crc = (uint16_t)((uint16_t)(crc << 4U) ^ tab[((crc >> 12U) ^ (data[i] & 0x0FU)) & 0x0FU]);
    }
    return crc;
}
