# Layer: output. Modules and the objects of the modules each one uses.
MODULES += listing results_gmsh
$(OBJDIR)/listing.o: $(OBJDIR)/blas_info.o $(OBJDIR)/contact.o $(OBJDIR)/kinds.o $(OBJDIR)/materials.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/solver_codes.o $(OBJDIR)/strings.o
$(OBJDIR)/results_gmsh.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/materials.o $(OBJDIR)/messages.o $(OBJDIR)/model.o
