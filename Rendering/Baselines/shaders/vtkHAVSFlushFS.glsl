//VTK::System::Dec
//HAVS::Defines::Dec

// HAVS flush pass: one full-viewport quad composites the entries each pixel's k-buffer still
// holds after the last face, in depth order.

in vec2 texCoord; // pixel centers: (x + 0.5) / width, (y + 0.5) / height

//HAVS::KBuffer::Impl

void main()
{
#ifdef HAVS_CLIPPING_PLANES
  clipRay(texCoord * 2.0 - 1.0);
#endif
  KBUFFER_BEGIN_CRITICAL_SECTION;
  loadKBuffer();
  if (accumulated.a < OPAQUE_ALPHA)
  {
    flushKBuffer(modelLengthPerDistance(texCoord * 2.0 - 1.0));
    storeKBuffer();
  }
  KBUFFER_END_CRITICAL_SECTION;
}
