/* VirtuoseAPI.h: the name Virtuose applications include ("#include \"VirtuoseAPI.h\""). The
 * compiler finds it through the hapticctrl package's include flags (pkg-config hapticctrl, or
 * linking hapticctrl::client), without it being put at the top of the system's include directory,
 * where Haption's own SDK could also be. hapticctrl's C API, with VirtuoseAPI 4.x's names and
 * values; docs/virtuose_api.md gives each function's status. Included by its place beside this
 * file, so that the one include directory a build written for Haption's SDK gives (J6) is
 * enough. */
#include "../virtuose_api.h"
