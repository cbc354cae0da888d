/*
 * Stand-in for Windows' bcryptprimitives.dll, for running MinGW-built test programs
 * under Debian's Wine 8, which lacks that DLL. Rust's std (1.78 and later) asks it for
 * random bytes (ProcessPrng) when it seeds its hash maps; Windows 10 and later ship the
 * real DLL, so this file is never part of a release. The bytes come from Wine's
 * RtlGenRandom (advapi32's SystemFunction036), Windows' older documented source.
 */
#include <windows.h>

BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length);

BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T size) {
    while (size > 0) {
        ULONG chunk = size > 0x10000000 ? 0x10000000 : (ULONG)size;
        if (!SystemFunction036(data, chunk)) return FALSE;
        data += chunk;
        size -= chunk;
    }
    return TRUE;
}
