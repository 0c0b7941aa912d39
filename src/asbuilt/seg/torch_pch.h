// Precompiled header for the LibTorch translation units of seg/ (issue 6:
// torch/torch.h alone costs ~22 s per file). Internal to seg/.
#include <torch/torch.h>
