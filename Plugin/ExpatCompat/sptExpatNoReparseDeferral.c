/*
 * Preloaded into ParaView 5.11 (LD_PRELOAD), turns off expat's reparse deferral in every XML
 * parser the process creates.
 *
 * Why: VTK 9.2's XML reader hands expat a file in pieces and assumes that expat has parsed
 * each piece to its end. Expat's reparse deferral (added against CVE-2023-52425, and present
 * in Debian 12's expat 2.5.0-1+deb12u5) may hold a token back for the next piece, and VTK then
 * reports "not well-formed (invalid token)". Besides .vtu files, this breaks ParaView's own
 * data exchange between MPI ranks (VTK's DIY utilities serialize data sets as XML), so the
 * redistribution for ordered compositing loses every piece that changes rank. Expat's
 * XML_SetReparseDeferralEnabled() is the documented switch; this library applies it.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <expat.h>
#include <stddef.h>

typedef XML_Parser (*ParserCreateFunction)(
  const XML_Char*, const XML_Memory_Handling_Suite*, const XML_Char*);

XML_Parser XML_ParserCreate_MM(
  const XML_Char* encoding, const XML_Memory_Handling_Suite* memory, const XML_Char* separator)
{
  static ParserCreateFunction create = NULL;
  if (!create)
  {
    create = (ParserCreateFunction)dlsym(RTLD_NEXT, "XML_ParserCreate_MM");
  }
  XML_Parser parser = create ? create(encoding, memory, separator) : NULL;
  if (parser)
  {
    XML_SetReparseDeferralEnabled(parser, XML_FALSE);
  }
  return parser;
}

/* Expat's own XML_ParserCreate and XML_ParserCreateNS call XML_ParserCreate_MM inside the
 * library, past any interposition, so they are replaced too. */
XML_Parser XML_ParserCreate(const XML_Char* encoding)
{
  return XML_ParserCreate_MM(encoding, NULL, NULL);
}

XML_Parser XML_ParserCreateNS(const XML_Char* encoding, XML_Char separator)
{
  const XML_Char separators[2] = { separator, 0 };
  return XML_ParserCreate_MM(encoding, NULL, separators);
}
