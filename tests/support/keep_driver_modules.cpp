// Preloaded (LD_PRELOAD) into the tests of the sanitizer build only, by the `asan` test preset.
//
// Mesa unloads its drivers (swrast_dri.so, libvulkan_lvp.so) and the Vulkan loader unloads the
// validation layer when a device or instance is destroyed. Allocations they never free are
// then reported by LeakSanitizer at exit with frames in unmapped memory, which no suppression
// can name. Keeping every module mapped until exit lets scripts/lsan.supp suppress exactly
// those modules, while leaks whose allocating frame is in loom's own code are still reported.
extern "C" int dlclose(void* handle) {
    (void)handle;
    return 0;
}
