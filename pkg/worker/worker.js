// The module worker `TrackerWorker.create` starts: the tracker's request loop (serve.js) with
// no ops of its own.
import { serve } from './serve.js';

serve();
