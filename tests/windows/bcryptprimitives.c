/* Test harness only: Debian's Wine 8 has no bcryptprimitives.dll, whose ProcessPrng Rust's
 * standard library imports for random numbers (HashMap seeds). This stand-in answers it from
 * Wine's BCryptGenRandom; real Windows (10 and later) has the DLL and never sees this file.
 * Built by tests/windows.sh into the Wine prefix's system32 when Wine lacks the DLL. */
#include <windows.h>
#include <bcrypt.h>

BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T len)
{
    while (len > 0) {
        ULONG n = len > 0x40000000 ? 0x40000000 : (ULONG)len;
        if (BCryptGenRandom(NULL, data, n, BCRYPT_USE_SYSTEM_PREFERRED_RNG) != 0)
            return FALSE;
        data += n;
        len -= n;
    }
    return TRUE;
}
