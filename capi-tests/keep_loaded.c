/*
 * Linked into the test programs only when they are built with AddressSanitizer: makes dlclose() a no-op.
 *
 * LeakSanitizer reports at exit, after the Vulkan loader has dlclose()d the driver (lavapipe, with the LLVM it
 * JITs with) and the validation layer. Blocks those libraries leaked then show only "<unknown module>" frames,
 * which no suppression can match and nobody can read. With the modules still mapped at exit, every frame names
 * its library, and lsan.supp can suppress exactly the leaks that are not dnsr's or the tests'.
 *
 * The executable's definition interposes on the loader's calls (the executable comes first in symbol lookup).
 * Nothing else changes: vkDestroyDevice/vkDestroyInstance still run, and the validation layer still reports
 * objects left alive.
 */
int dlclose(void *handle);

int dlclose(void *handle)
{
    (void)handle;
    return 0;
}
