/* What the Makefile found on the build machine, for solver_codes.f90:
 * CFE_HAVE_MUMPS is defined when MUMPS and MPI were there (the MUMPS
 * backend is then real; otherwise mumps_shim.c has only stubs). */
int cfe_build_has_mumps(void)
{
#ifdef CFE_HAVE_MUMPS
  return 1;
#else
  return 0;
#endif
}
