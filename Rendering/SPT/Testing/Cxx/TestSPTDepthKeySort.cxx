// The pass between a group's key and color traversals (vtkSPTDepthKeyBuffer::PrepareSurvivors)
// sorts each sample's keys for the visibility estimator, each half of the group apart: the
// color traversal counts the survivors behind a fragment by binary search in them. The sort
// gathers the kept keys and sorts only those, filling the rest of each half with "nothing
// kept". Its result must be what std::sort gives for each half.
//
// Random keys are written into the buffer and sorted on the GPU, for groups of 1 to 64
// repetitions, halves split anywhere (none, in the middle, off the middle, at the end), a
// group shorter than the buffer's layers, and samples where no repetition, some, or every
// repetition kept a fragment, with ties. Without the sort (the survivor estimator), the keys
// keep their order.

#include "vtkSPTDepthKeyBuffer.h"

#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTesting.h"

#include "SPTTestWindow.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <random>
#include <vector>

namespace
{
constexpr unsigned int NothingKept = 0xFFFFFFFFu;
constexpr int Size = 12; // samples per side
constexpr int Unit = 0;  // the image unit of the keys

// Keys of layers x Size x Size samples, in the buffer's order (layer fastest). Each sample
// keeps a fragment in a fraction of the repetitions that varies over the image, from none to
// all; a few keys repeat, as two fragments at one depth of one cell would.
std::vector<unsigned int> RandomKeys(int layers, std::mt19937& random)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<unsigned int> key(0u, 0xFFFFFF00u);
  std::vector<unsigned int> keys(size_t(layers) * Size * Size);
  for (int sample = 0; sample < Size * Size; ++sample)
  {
    const double kept = sample % 7 == 0 ? 0.0 : (sample % 11 == 0 ? 1.0 : unit(random));
    for (int r = 0; r < layers; ++r)
    {
      unsigned int& k = keys[size_t(sample) * layers + r];
      k = unit(random) < kept ? key(random) : NothingKept;
      if (r > 0 && k != NothingKept && unit(random) < 0.1)
      {
        k = keys[size_t(sample) * layers + r - 1]; // a tie (or "nothing kept")
      }
    }
  }
  return keys;
}

// What the pass must leave: the first `repetitions` layers of each sample sorted in
// [0, split) and [split, repetitions) apart; the layers beyond, as they were.
std::vector<unsigned int> Expected(
  std::vector<unsigned int> keys, int layers, int repetitions, int split, bool sort)
{
  if (!sort)
  {
    return keys;
  }
  for (int sample = 0; sample < Size * Size; ++sample)
  {
    auto first = keys.begin() + size_t(sample) * layers;
    std::sort(first, first + split);
    std::sort(first + split, first + repetitions);
  }
  return keys;
}

int Check(vtkOpenGLRenderWindow* context, vtkSPTDepthKeyBuffer* buffer, int layers, int repetitions,
  int split, bool sort, std::mt19937& random)
{
  if (!buffer->Prepare(context, Size, Size, layers))
  {
    std::cerr << "Could not allocate " << layers << " layers of keys.\n";
    return 1;
  }
  const std::vector<unsigned int> keys = RandomKeys(layers, random);
  buffer->Write(keys);
  vtkOpenGLState* ostate = context->GetState();
  ostate->vtkglViewport(0, 0, Size, Size);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  buffer->BindImage(Unit);
  vtkSPTDepthKeyBuffer::Barrier();
  const bool ran = buffer->PrepareSurvivors(Unit, Unit + 1, repetitions, split, sort);
  vtkSPTDepthKeyBuffer::Barrier();
  vtkSPTDepthKeyBuffer::UnbindImage(Unit);
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  if (!ran)
  {
    std::cerr << "The survivors' pass did not run (" << layers << " layers).\n";
    return 1;
  }
  const std::vector<unsigned int> sorted = buffer->Read();
  const std::vector<unsigned int> expected = Expected(keys, layers, repetitions, split, sort);
  for (size_t i = 0; i < expected.size(); ++i)
  {
    if (sorted[i] != expected[i])
    {
      std::cerr << "Layers " << layers << ", repetitions " << repetitions << ", split " << split
                << (sort ? ", sorted" : ", unsorted") << ": sample " << i / layers << ", layer "
                << i % layers << " holds " << sorted[i] << ", expected " << expected[i] << ".\n";
      return 1;
    }
  }
  return 0;
}
}

int TestSPTDepthKeySort(int, char*[])
{
  SPTTestWindow::RawContext raw(Size);
  if (!raw.Context || !vtkSPTDepthKeyBuffer::IsSupported(raw.Context))
  {
    std::cout << "The context has no image load/store; the keys are not used.\n";
    return VTK_SKIP_RETURN_CODE;
  }
  std::mt19937 random(2009);
  int failures = 0;
  struct Group
  {
    int Layers;
    int Repetitions;
    int Split;
  };
  const Group groups[] = { { 1, 1, 1 }, { 1, 1, 0 }, { 2, 2, 1 }, { 5, 5, 5 }, { 16, 16, 8 },
    { 16, 16, 16 }, { 16, 16, 0 }, { 16, 11, 5 }, { 32, 32, 13 }, { 64, 64, 32 }, { 64, 40, 40 } };
  for (const Group& group : groups)
  {
    for (bool sort : { true, false })
    {
      vtkNew<vtkSPTDepthKeyBuffer> buffer;
      failures +=
        Check(raw.Context, buffer, group.Layers, group.Repetitions, group.Split, sort, random);
      buffer->ReleaseGraphicsResources(raw.Context);
    }
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
