def reconstruction_error(ma, shape): raise NotImplementedError
