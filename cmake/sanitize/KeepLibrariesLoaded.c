/* Linked into every program of a GPUDEM_SANITIZE build: a dlclose that keeps the library
 * loaded. Open MPI unloads its components at MPI_Finalize, before LeakSanitizer reports at exit,
 * so the allocations they make (and keep: Open MPI frees little of what MPI_Init allocates)
 * would show as leaks in an unknown module that no suppression can name. Kept loaded, they
 * carry their library's name, which cmake/sanitize/lsan-suppressions.txt lists. */
int dlclose(void* handle) {
  (void)handle;
  return 0;
}
