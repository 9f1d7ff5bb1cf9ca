/* Test harness only: holds a file open the way a G-code sender does (read access; others may
 * read it but neither write, rename nor delete it), so tests/windows/cli.sh can show what
 * millpath.exe does when it must replace a file another program has open.
 * Usage: holdopen FILE RELEASE. Prints "held PID" once FILE is open (its process id: a
 * live process for the stale-file sweep's test), keeps it open until a file
 * RELEASE exists (at most a minute), then closes it. */
#include <windows.h>
#include <stdio.h>

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: holdopen FILE RELEASE\n");
        return 2;
    }
    HANDLE h = CreateFileA(argv[1], GENERIC_READ, FILE_SHARE_READ, NULL, OPEN_EXISTING,
                           FILE_ATTRIBUTE_NORMAL, NULL);
    if (h == INVALID_HANDLE_VALUE) {
        fprintf(stderr, "holdopen: cannot open %s (error %lu)\n", argv[1], GetLastError());
        return 1;
    }
    printf("held %lu\n", (unsigned long)GetCurrentProcessId());
    fflush(stdout);
    for (int i = 0; i < 600 && GetFileAttributesA(argv[2]) == INVALID_FILE_ATTRIBUTES; i++)
        Sleep(100);
    CloseHandle(h);
    return 0;
}
